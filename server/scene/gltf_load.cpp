// load_gltf_file and load_glb_bytes: read safely (gltf_read), convert (gltf_mesh, gltf_nodes,
// gltf_skins, gltf_animation, gltf_extras), validate. Files that strata did not write (no extras.strata) get
// the glTF scene's name (else the file's stem), and a white environment of radiance 1 when no
// material emits, so that they are visible at all; otherwise the environment is black. A file whose
// scene has no triangles is refused: there is nothing to render.
#include "scene/gltf_convert.h"
#include "scene/gltf_extensions.h"
#include "scene/gltf_extras.h"
#include "scene/gltf_read.h"
#include "scene/scene_io.h"
#include "scene/triangle_order.h"

namespace strata::scene {
namespace {

bool has_emitter(const Scene& scene) {
  for (const Material& m : scene.materials) {
    if (glm::any(glm::greaterThan(m.emission, glm::vec3(0.0f)))) return true;
  }
  return false;
}

void require_geometry(const gltf::Source& source, const gltf::NodeTree& tree, const Scene& scene) {
  const std::string what = source.label + ": the scene has no geometry: ";
  if (scene.instances.empty()) {
    if (source.model.nodes.empty()) throw SceneError(what + "the file has no nodes");
    if (tree.scene_index < 0) throw SceneError(what + "none of its nodes has a mesh");
    const std::string field = gltf::at("scenes", static_cast<size_t>(tree.scene_index));
    if (source.model.scenes[static_cast<size_t>(tree.scene_index)].nodes.empty())
      throw SceneError(what + field + ".nodes is empty");
    throw SceneError(what + "none of the nodes of " + field + " has a mesh");
  }
  for (const Instance& instance : scene.instances) {
    for (uint32_t mesh : instance.lod_meshes) {
      for (const Primitive& p : scene.meshes[mesh].primitives) {
        if (p.triangle_count() > 0) return;
      }
    }
  }
  throw SceneError(what + "the meshes of its " + gltf::count_of(scene.instances.size(), "instance") +
                   " have no triangles");
}

Scene convert(const tinygltf::Model& model, const std::string& label,
              const std::string& fallback_name, const LoadLimits& limits) {
  const gltf::Source source{model, label, limits};
  Scene scene;
  gltf::convert_materials(source, scene);
  gltf::convert_material_textures(source, scene);
  gltf::convert_meshes(source, scene);
  gltf::NodeTree tree = gltf::convert_nodes(source, scene);
  gltf::convert_skins(source, tree, scene);
  gltf::convert_lights(source, tree, scene);
  require_geometry(source, tree, scene);
  gltf::convert_animations(source, tree, scene);
  gltf::list_ignored_features(source, scene);
  if (!gltf::read_scene_extras(source, tree.scene_index, scene)) {
    const std::string gltf_name =
        tree.scene_index >= 0 ? model.scenes[static_cast<size_t>(tree.scene_index)].name : "";
    scene.name = gltf_name.empty() ? fallback_name : gltf_name;
    if (!has_emitter(scene)) scene.environment.radiance = glm::vec3(1.0f);
  }
  try {
    scene.validate();
  } catch (const SceneError& e) {
    throw SceneError(label + ": " + e.what());
  }
  sort_triangles_spatially(scene);
  return scene;
}

}  // namespace

Scene load_gltf_file(const std::filesystem::path& path, const LoadLimits& limits) {
  const std::vector<uint8_t> bytes = gltf::read_file(path, limits);
  std::error_code ec;
  const std::filesystem::path directory = std::filesystem::absolute(path, ec).parent_path();
  if (ec) throw SceneError(path.string() + ": cannot resolve its directory: " + ec.message());
  const tinygltf::Model model =
      gltf::parse_model(bytes, path.string(), directory, limits.max_file_bytes - bytes.size());
  return convert(model, path.string(), path.stem().string(), limits);
}

Scene load_glb_bytes(std::span<const uint8_t> bytes, const std::string& label,
                     const LoadLimits& limits) {
  if (bytes.size() > limits.max_file_bytes) {
    throw SceneError(label + ": " + std::to_string(bytes.size()) +
                     " bytes, over LoadLimits::max_file_bytes (" +
                     std::to_string(limits.max_file_bytes) + ")");
  }
  const tinygltf::Model model = gltf::parse_model(bytes, label, std::nullopt, 0);
  return convert(model, label, label, limits);
}

}  // namespace strata::scene
