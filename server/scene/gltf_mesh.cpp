// glTF materials and meshes to Scene materials and meshes.
#include <cmath>
#include <numeric>

#include "scene/gltf_accessor.h"
#include "scene/gltf_convert.h"
#include "scene/gltf_extensions.h"
#include "scene/gltf_mesh_deform.h"
#include "scene/normals.h"

namespace strata::scene::gltf {
namespace {

const char* kEmissiveStrength = "KHR_materials_emissive_strength";

double emissive_strength(const Source& s, const tinygltf::Material& m, const std::string& field) {
  const auto it = m.extensions.find(kEmissiveStrength);
  if (it == m.extensions.end() || !it->second.IsObject() || !it->second.Has("emissiveStrength"))
    return 1.0;
  const tinygltf::Value& v = it->second.Get("emissiveStrength");
  const std::string name = field + ".extensions." + kEmissiveStrength + ".emissiveStrength";
  if (!v.IsNumber() || !(v.GetNumberAsDouble() >= 0.0))
    s.fail(name, "must be a non-negative number");
  return v.GetNumberAsDouble();
}

const char* kSpecular = "KHR_materials_specular";

// KHR_materials_specular's specularFactor (default 1): strata scales the dielectric F0 by it, so 0
// gives a pure Lambert surface. specularColorFactor is not supported and is ignored.
float specular_factor(const Source& s, const tinygltf::Material& m, const std::string& field) {
  const auto it = m.extensions.find(kSpecular);
  if (it == m.extensions.end() || !it->second.IsObject() || !it->second.Has("specularFactor")) return 1.0f;
  const tinygltf::Value& v = it->second.Get("specularFactor");
  const std::string name = field + ".extensions." + kSpecular + ".specularFactor";
  if (!v.IsNumber() || !(v.GetNumberAsDouble() >= 0.0) || !(v.GetNumberAsDouble() <= 1.0))
    s.fail(name, "must be a number in [0, 1]");
  return to_float(v.GetNumberAsDouble());
}

struct MeshState {
  size_t triangles = 0;
  std::optional<uint32_t> default_material;
  size_t target_vertices = 0;  // morph target vertices over the file (gltf_mesh_deform.h)
  size_t renormalised = 0;     // vertices of the current mesh whose WEIGHTS_0 were renormalised
};

uint32_t material_of(const Source& s, const tinygltf::Primitive& p, const std::string& field,
                     Scene& scene, MeshState& state) {
  if (p.material == -1) {
    if (!state.default_material) {
      Material fallback;
      fallback.name = "default";
      scene.materials.push_back(fallback);
      state.default_material = static_cast<uint32_t>(scene.materials.size() - 1);
    }
    return *state.default_material;
  }
  s.check_index(field + ".material", p.material, s.model.materials.size(), "materials");
  return static_cast<uint32_t>(p.material);
}

// A TRIANGLE_STRIP or TRIANGLE_FAN as a triangle list, with the vertex order glTF 2.0 gives
// (section 3.7.2.1): strip triangle i is {v_i, v_i+(1+i%2), v_i+(2-i%2)}, fan triangle i is
// {v_i+1, v_i+2, v_0}, so every triangle keeps the winding of the first.
std::vector<uint32_t> triangle_list(const std::vector<uint32_t>& v, int mode) {
  std::vector<uint32_t> out;
  if (v.size() < 3) return out;
  out.reserve(3 * (v.size() - 2));
  for (size_t i = 0; i + 2 < v.size(); ++i) {
    if (mode == TINYGLTF_MODE_TRIANGLE_STRIP) {
      out.insert(out.end(), {v[i], v[i + 1 + i % 2], v[i + 2 - i % 2]});
    } else {
      out.insert(out.end(), {v[i + 1], v[i + 2], v[0]});
    }
  }
  return out;
}

// Keeps normals within 1e-3 of unit length as they are, normalises the rest and replaces the
// ones that cannot be normalised by the generated normal.
void repair_normals(Primitive& out) {
  std::vector<glm::vec3> generated;
  for (size_t v = 0; v < out.normals.size(); ++v) {
    const float length = glm::length(out.normals[v]);
    if (std::abs(length - 1.0f) <= 1e-3f) continue;
    if (length > 1e-12f) {
      out.normals[v] /= length;
    } else {
      if (generated.empty()) generated = area_weighted_normals(out.positions, out.indices);
      out.normals[v] = generated[v];
    }
  }
}

// TEXCOORD_1 where a texture of the material reads set 1, TANGENT where the material has a normal
// texture (tangents are unit length in xyz, w = +-1); neither is kept otherwise.
void read_texture_attributes(const Source& s, const tinygltf::Primitive& p, const std::string& field,
                             const Material& material, size_t vertices, Primitive& out) {
  bool set1 = false;
  for (const TextureRef* ref : {&material.base_color_texture, &material.metallic_roughness_texture,
                                &material.normal_texture, &material.emissive_texture}) {
    set1 = set1 || (ref->texture >= 0 && ref->tex_coord == 1);
  }
  auto checked = [&](const char* name) -> int {
    const auto it = p.attributes.find(name);
    if (it == p.attributes.end()) return -1;
    const std::string attr_field = field + ".attributes." + name;
    const size_t count = accessor_count(s, it->second, attr_field);
    if (count != vertices) {
      s.fail(attr_field, "has " + std::to_string(count) + " elements, POSITION has " + std::to_string(vertices));
    }
    return it->second;
  };
  if (set1) {
    const int accessor = checked("TEXCOORD_1");
    if (accessor < 0) {
      s.fail(field + ".attributes.TEXCOORD_1",
             "is missing (materials[" + std::to_string(out.material) + "] reads texture coordinate set 1)");
    }
    out.uvs1 = read_vec2(s, accessor, Components::kFloatOrNormalizedUnsigned, field + ".attributes.TEXCOORD_1");
  }
  if (material.normal_texture.texture >= 0) {
    const int accessor = checked("TANGENT");
    if (accessor < 0) return;
    const std::string attr_field = field + ".attributes.TANGENT";
    const std::vector<float> v = read_floats(s, accessor, 4, Components::kFloatOnly, attr_field);
    out.tangents.resize(vertices);
    for (size_t i = 0; i < vertices; ++i) {
      const glm::vec3 t(v[4 * i], v[4 * i + 1], v[4 * i + 2]);
      const float length = glm::length(t);
      if (!(length > 1e-12f)) s.fail(at(attr_field, i), "is not a direction (zero length)");
      out.tangents[i] = glm::vec4(t / length, v[4 * i + 3] < 0.0f ? -1.0f : 1.0f);
    }
  }
}

Primitive convert_primitive(const Source& s, const tinygltf::Primitive& p, const std::string& field,
                            Scene& scene, MeshState& state) {
  const bool list = p.mode == TINYGLTF_MODE_TRIANGLES;
  if (!list && p.mode != TINYGLTF_MODE_TRIANGLE_STRIP && p.mode != TINYGLTF_MODE_TRIANGLE_FAN) {
    constexpr const char* kNames[] = {"POINTS", "LINES", "LINE_LOOP", "LINE_STRIP"};
    const std::string name =
        p.mode >= 0 && p.mode < 4 ? std::string(" (") + kNames[p.mode] + ")" : std::string();
    s.fail(field + ".mode", "= " + std::to_string(p.mode) + name +
                                " is not supported: strata renders triangles (TRIANGLES, "
                                "TRIANGLE_STRIP and TRIANGLE_FAN, modes 4 to 6)");
  }
  const auto pos_it = p.attributes.find("POSITION");
  if (pos_it == p.attributes.end()) s.fail(field + ".attributes.POSITION", "is missing");
  const std::string pos_field = field + ".attributes.POSITION";
  const size_t vertices = accessor_count(s, pos_it->second, pos_field);
  if (p.indices < -1)
    s.check_index(field + ".indices", p.indices, s.model.accessors.size(), "accessors");
  // Count triangles before reading anything large, so an oversized file fails fast.
  const size_t corners =
      p.indices >= 0 ? accessor_count(s, p.indices, field + ".indices") : vertices;
  state.triangles += list ? corners / 3 : corners >= 3 ? corners - 2 : 0;
  if (state.triangles > s.limits.max_triangles) {
    s.fail(field, "brings the triangle count to " + std::to_string(state.triangles) +
                      ", over LoadLimits::max_triangles (" +
                      std::to_string(s.limits.max_triangles) + ")");
  }

  Primitive out;
  out.material = material_of(s, p, field, scene, state);
  out.positions = read_vec3(s, pos_it->second, Components::kFloatOnly, pos_field);
  if (p.indices >= 0) {
    out.indices = read_indices(s, p.indices, field + ".indices");
  } else {
    if (list && vertices % 3 != 0)
      s.fail(field,
             "has " + std::to_string(vertices) + " vertices and no indices, not a multiple of 3");
    out.indices.resize(vertices);
    std::iota(out.indices.begin(), out.indices.end(), 0u);
  }
  if (list && out.indices.size() % 3 != 0) {
    s.fail(field + ".indices",
           "has " + std::to_string(out.indices.size()) + " entries, not a multiple of 3");
  }
  for (size_t k = 0; k < out.indices.size(); ++k) {
    if (out.indices[k] >= vertices) {
      s.fail(at(field + ".indices", k), "= " + std::to_string(out.indices[k]) +
                                            " is out of range (" + std::to_string(vertices) +
                                            " vertices)");
    }
  }
  if (!list) out.indices = triangle_list(out.indices, p.mode);
  for (const char* name : {"NORMAL", "TEXCOORD_0"}) {
    const auto it = p.attributes.find(name);
    if (it == p.attributes.end()) continue;
    const std::string attr_field = field + ".attributes." + name;
    const size_t count = accessor_count(s, it->second, attr_field);
    if (count != vertices) {
      s.fail(attr_field, "has " + std::to_string(count) + " elements, POSITION has " +
                             std::to_string(vertices));
    }
    if (std::string(name) == "NORMAL") {
      out.normals = read_vec3(s, it->second, Components::kFloatOrNormalized, attr_field);
    } else {
      out.uvs = read_vec2(s, it->second, Components::kFloatOrNormalizedUnsigned, attr_field);
    }
  }
  read_texture_attributes(s, p, field, scene.materials[out.material], vertices, out);
  state.renormalised += read_skin_attributes(s, p, field, vertices, out);
  read_morph_targets(s, p, field, vertices, state.target_vertices, out);
  // Normals a file leaves out are generated from the rest pose, with no morph target applied; a
  // target's NORMAL deltas (when it has any) move them as they would move the file's own normals.
  if (out.normals.empty()) {
    out.normals = area_weighted_normals(out.positions, out.indices);
  } else {
    repair_normals(out);
  }
  if (out.uvs.empty()) out.uvs.assign(vertices, glm::vec2(0.0f));
  return out;
}

}  // namespace

void convert_materials(const Source& s, Scene& scene) {
  for (size_t i = 0; i < s.model.materials.size(); ++i) {
    const tinygltf::Material& m = s.model.materials[i];
    const std::string field = at("materials", i);
    const auto& pbr = m.pbrMetallicRoughness;
    if (pbr.baseColorFactor.size() != 4)
      s.fail(field + ".pbrMetallicRoughness.baseColorFactor", "must hold 4 numbers");
    if (m.emissiveFactor.size() != 3) s.fail(field + ".emissiveFactor", "must hold 3 numbers");
    Material out;
    out.name = m.name;
    out.base_color = {to_float(pbr.baseColorFactor[0]), to_float(pbr.baseColorFactor[1]),
                      to_float(pbr.baseColorFactor[2])};
    out.metallic = to_float(pbr.metallicFactor);
    out.roughness = to_float(pbr.roughnessFactor);
    // The product is formed in double: the exporter splits an emission e into e / s and s in
    // double, and only a double product rounds back to e exactly.
    const double strength = emissive_strength(s, m, field);
    for (int c = 0; c < 3; ++c)
      out.emission[c] = to_float(m.emissiveFactor[static_cast<size_t>(c)] * strength);
    out.double_sided = m.doubleSided;
    out.specular = specular_factor(s, m, field);
    scene.materials.push_back(out);
  }
}

void convert_meshes(const Source& s, Scene& scene) {
  MeshState state;
  for (size_t m = 0; m < s.model.meshes.size(); ++m) {
    const tinygltf::Mesh& mesh = s.model.meshes[m];
    if (mesh.primitives.empty()) {
      s.fail(at("meshes", m) + ".primitives",
             "is empty or not an array (a mesh needs at least one primitive)");
    }
    Mesh out;
    out.name = mesh.name;
    state.renormalised = 0;
    for (size_t p = 0; p < mesh.primitives.size(); ++p) {
      out.primitives.push_back(convert_primitive(
          s, mesh.primitives[p], at(at("meshes", m) + ".primitives", p), scene, state));
    }
    out.weights = read_mesh_weights(s, mesh, at("meshes", m), out);
    if (state.renormalised > 0) {
      scene.ignored_features.push_back(
          "WEIGHTS_0 renormalised on " + count_of(state.renormalised, "vertex", "vertices") + " of " +
          (mesh.name.empty() ? at("meshes", m) : "mesh '" + mesh.name + "'") +
          " (their sums were off 1 by more than 1e-3)");
    }
    scene.meshes.push_back(std::move(out));
  }
}

}  // namespace strata::scene::gltf
