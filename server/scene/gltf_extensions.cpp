// Which glTF extensions strata renders, the refusal of files that require any other, and the list of
// what a loaded file holds that the scene model leaves out (Scene::ignored_features).
#include "scene/gltf_extensions.h"

#include <algorithm>
#include <array>
#include <map>
#include <set>
#include <utility>
#include <vector>

#include <nlohmann/json.hpp>

namespace strata::scene::gltf {
namespace {

// Extensions whose content reaches the scene model.
constexpr std::array<std::string_view, 5> kRendered = {
    "KHR_lights_punctual",              // Scene::lights
    "KHR_materials_emissive_strength",  // Material::emission
    "KHR_materials_specular",           // specularFactor only; the rest is listed as ignored
    "KHR_texture_transform",            // TextureRef::transform
    "MSFT_lod",                         // Instance::lod_meshes
};

struct Known {
  std::string_view name;
  std::string_view what;  // what the extension carries, for refusals
  std::string_view note;  // how a file that only uses it is rendered, for the ignored list
};

// Extensions strata does not render that are common enough to deserve words of their own; any
// other unrendered extension is named without them.
constexpr std::array<Known, 22> kKnown = {{
    {"KHR_draco_mesh_compression", "Draco-compressed meshes", "the uncompressed fallback is used"},
    {"EXT_meshopt_compression", "meshoptimizer-compressed buffers", "the uncompressed fallback is used"},
    {"KHR_mesh_quantization", "quantized vertex attributes", ""},
    {"KHR_texture_basisu", "KTX2 / Basis Universal textures", "the PNG/JPEG fallback source is used"},
    {"EXT_texture_webp", "WebP textures", "the PNG/JPEG fallback source is used"},
    {"EXT_texture_avif", "AVIF textures", "the PNG/JPEG fallback source is used"},
    {"MSFT_texture_dds", "DDS textures", "the PNG/JPEG fallback source is used"},
    {"KHR_technique_webgl", "GLSL shader techniques", "rendered with the glTF materials"},
    {"KHR_materials_pbrSpecularGlossiness", "the specular-glossiness material model",
     "rendered with their metallic-roughness values"},
    {"KHR_materials_clearcoat", "clear-coat layers", "rendered without the coat"},
    {"KHR_materials_transmission", "transmissive materials", "rendered opaque"},
    {"KHR_materials_volume", "volumetric materials", "rendered as surfaces"},
    {"KHR_materials_sheen", "sheen layers", "rendered without the sheen"},
    {"KHR_materials_iridescence", "iridescence", "rendered without it"},
    {"KHR_materials_anisotropy", "anisotropic specular", "rendered isotropic"},
    {"KHR_materials_ior", "indices of refraction", "rendered with IOR 1.5"},
    {"KHR_materials_dispersion", "dispersion", "rendered without it"},
    {"KHR_materials_unlit", "unlit materials", "rendered lit"},
    {"KHR_materials_variants", "material variants", "the default materials are used"},
    {"EXT_mesh_gpu_instancing", "GPU instancing", "each node is drawn once"},
    {"KHR_animation_pointer", "animated properties", "those animations are not played"},
    {"KHR_xmp_json_ld", "XMP metadata", "metadata only"},
}};

const Known* known(std::string_view name) {
  for (const Known& k : kKnown) {
    if (k.name == name) return &k;
  }
  return nullptr;
}

// The objects of the file carrying each extension, counted per kind of object.
class ExtensionUse {
 public:
  void add(const tinygltf::ExtensionMap& extensions, std::string_view kind, size_t object) {
    for (const auto& [name, value] : extensions) uses_[name][std::string(kind)].insert(object);
  }
  void declare(const std::string& name) { uses_[name]; }
  const std::map<std::string, std::map<std::string, std::set<size_t>>>& uses() const { return uses_; }

 private:
  // extension -> object kind ("material") -> indices of the objects carrying it
  std::map<std::string, std::map<std::string, std::set<size_t>>> uses_;
};

constexpr std::string_view kTopLevel = "the top level";

ExtensionUse collect(const tinygltf::Model& m) {
  ExtensionUse use;
  for (const std::string& name : m.extensionsUsed) use.declare(name);
  use.add(m.extensions, kTopLevel, 0);
  for (size_t i = 0; i < m.materials.size(); ++i) {
    const tinygltf::Material& mat = m.materials[i];
    use.add(mat.extensions, "material", i);
    const auto& pbr = mat.pbrMetallicRoughness;
    use.add(pbr.extensions, "material", i);
    for (const tinygltf::ExtensionMap* info :
         {&pbr.baseColorTexture.extensions, &pbr.metallicRoughnessTexture.extensions,
          &mat.normalTexture.extensions, &mat.occlusionTexture.extensions,
          &mat.emissiveTexture.extensions}) {
      use.add(*info, "material", i);
    }
  }
  for (size_t i = 0; i < m.textures.size(); ++i) use.add(m.textures[i].extensions, "texture", i);
  for (size_t i = 0; i < m.images.size(); ++i) use.add(m.images[i].extensions, "image", i);
  for (size_t i = 0; i < m.samplers.size(); ++i) use.add(m.samplers[i].extensions, "sampler", i);
  for (size_t i = 0; i < m.nodes.size(); ++i) use.add(m.nodes[i].extensions, "node", i);
  for (size_t i = 0; i < m.meshes.size(); ++i) {
    use.add(m.meshes[i].extensions, "mesh", i);
    for (const tinygltf::Primitive& p : m.meshes[i].primitives) use.add(p.extensions, "mesh", i);
  }
  for (size_t i = 0; i < m.cameras.size(); ++i) use.add(m.cameras[i].extensions, "camera", i);
  for (size_t i = 0; i < m.scenes.size(); ++i) use.add(m.scenes[i].extensions, "scene", i);
  for (size_t i = 0; i < m.animations.size(); ++i) use.add(m.animations[i].extensions, "animation", i);
  for (size_t i = 0; i < m.skins.size(); ++i) use.add(m.skins[i].extensions, "skin", i);
  for (size_t i = 0; i < m.accessors.size(); ++i) use.add(m.accessors[i].extensions, "accessor", i);
  for (size_t i = 0; i < m.bufferViews.size(); ++i) use.add(m.bufferViews[i].extensions, "bufferView", i);
  for (size_t i = 0; i < m.buffers.size(); ++i) use.add(m.buffers[i].extensions, "buffer", i);
  return use;
}

// "KHR_materials_clearcoat on 3 materials (rendered without the coat)".
std::string describe_use(const std::string& name,
                         const std::map<std::string, std::set<size_t>>& kinds) {
  std::string where;
  bool top_level = false;
  for (const auto& [kind, objects] : kinds) {
    if (kind == kTopLevel) {
      top_level = true;
      continue;
    }
    where += (where.empty() ? " on " : ", ") +
             count_of(objects.size(), kind, kind == "mesh" ? "meshes" : "");
  }
  if (top_level) where += where.empty() ? " (at the top level)" : " and at the top level";
  if (kinds.empty()) return name + " (listed in extensionsUsed, on no object)";
  const Known* k = known(name);
  const std::string note = k != nullptr && !k->note.empty() ? " (" + std::string(k->note) + ")" : "";
  return name + where + note;
}

void list_extensions(const Source& s, Scene& scene) {
  const ExtensionUse use = collect(s.model);
  for (const auto& [name, kinds] : use.uses()) {
    if (is_rendered_extension(name)) continue;
    scene.ignored_features.push_back(describe_use(name, kinds));
  }
}

// KHR_materials_specular: strata scales the dielectric F0 by specularFactor; the colour and the
// textures of the extension are not rendered.
void list_specular_parts(const Source& s, Scene& scene) {
  size_t with_colour = 0;
  for (const tinygltf::Material& m : s.model.materials) {
    const auto it = m.extensions.find("KHR_materials_specular");
    if (it == m.extensions.end() || !it->second.IsObject()) continue;
    const tinygltf::Value& v = it->second;
    if (v.Has("specularColorFactor") || v.Has("specularTexture") || v.Has("specularColorTexture"))
      ++with_colour;
  }
  if (with_colour > 0) {
    scene.ignored_features.push_back(
        "KHR_materials_specular specularColorFactor and specular textures on " +
        count_of(with_colour, "material") + " (specularFactor is rendered)");
  }
}

void list_core_features(const Source& s, Scene& scene) {
  const tinygltf::Model& m = s.model;
  // Skins and morph targets are rendered; deltas of attributes other than POSITION and NORMAL are not.
  std::map<std::string, size_t> other_deltas;  // attribute -> meshes whose targets displace it
  size_t coloured = 0;
  for (const tinygltf::Mesh& mesh : m.meshes) {
    std::set<std::string> names;
    for (const tinygltf::Primitive& p : mesh.primitives) {
      coloured += p.attributes.count("COLOR_0");
      for (const std::map<std::string, int>& target : p.targets) {
        for (const auto& [name, accessor] : target) {
          if (name != "POSITION" && name != "NORMAL") names.insert(name);
        }
      }
    }
    for (const std::string& name : names) ++other_deltas[name];
  }
  for (const auto& [name, meshes] : other_deltas) {
    scene.ignored_features.push_back("morph target " + name + " deltas on " + count_of(meshes, "mesh", "meshes") +
                                     " (not applied: the rest pose's " + name + " is used)");
  }
  if (coloured > 0) {
    scene.ignored_features.push_back("COLOR_0 on " + count_of(coloured, "primitive") +
                                     " (vertex colours are not rendered)");
  }

  size_t occlusion = 0;
  for (const tinygltf::Material& mat : m.materials) occlusion += mat.occlusionTexture.index >= 0;
  if (occlusion > 0) {
    scene.ignored_features.push_back("occlusionTexture on " + count_of(occlusion, "material") +
                                     " (the path tracer computes occlusion itself)");
  }

  size_t orthographic = 0;
  for (const tinygltf::Node& n : m.nodes) {
    if (n.camera >= 0 && static_cast<size_t>(n.camera) < m.cameras.size() &&
        m.cameras[static_cast<size_t>(n.camera)].type == "orthographic") {
      ++orthographic;
    }
  }
  if (orthographic > 0) {
    scene.ignored_features.push_back("orthographic camera on " + count_of(orthographic, "node") +
                                     " (strata renders perspective cameras)");
  }
}

}  // namespace

bool is_rendered_extension(std::string_view name) {
  return std::find(kRendered.begin(), kRendered.end(), name) != kRendered.end();
}

std::string count_of(size_t count, std::string_view singular, std::string_view plural) {
  std::string noun(count == 1 ? singular : (plural.empty() ? std::string(singular) + "s" : plural));
  return std::to_string(count) + " " + noun;
}

void refuse_required_extensions(std::span<const uint8_t> json, const std::string& label) {
  // Keep only the top-level extensionsRequired array: the rest of the document (embedded buffers
  // included) is parsed and dropped.
  const nlohmann::json::parser_callback_t keep = [](int depth, nlohmann::json::parse_event_t event,
                                                     nlohmann::json& parsed) {
    if (event == nlohmann::json::parse_event_t::key && depth == 1)
      return parsed == "extensionsRequired";
    return true;
  };
  const nlohmann::json doc =
      nlohmann::json::parse(json.begin(), json.end(), keep, /*allow_exceptions=*/false);
  if (!doc.is_object() || !doc.contains("extensionsRequired")) return;
  const nlohmann::json& required = doc["extensionsRequired"];
  if (!required.is_array()) return;  // tinygltf reports the type
  std::vector<std::string> refused;
  for (const nlohmann::json& entry : required) {
    if (!entry.is_string() || is_rendered_extension(entry.get<std::string>())) continue;
    const std::string name = entry.get<std::string>();
    const Known* k = known(name);
    refused.push_back(k != nullptr ? name + " (" + std::string(k->what) + ")" : name);
  }
  if (refused.empty()) return;
  std::string names;
  for (size_t i = 0; i < refused.size(); ++i) {
    names += (i == 0 ? "" : i + 1 == refused.size() ? " and " : ", ") + refused[i];
  }
  throw SceneError(label + ": extensionsRequired lists " + names + ", which strata does not render");
}

void list_ignored_features(const Source& s, Scene& scene) {
  list_extensions(s, scene);
  list_specular_parts(s, scene);
  list_core_features(s, scene);
}

}  // namespace strata::scene::gltf
