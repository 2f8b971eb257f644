#pragma once
// strata's own data in glTF `extras`, written by the exporter and read by the loader; the key
// names live only here. On the default scene:
//   extras.strata = {name, environment: [r,g,b], aperture, focus_distance, frames_per_second,
//                    lod_schedule: [[time, instance, level], ...]}
// On an instance's node:
//   extras.strata = {lod: level at frame 0, rest_matrix: [16 numbers, column-major]}
// rest_matrix is written for animated instances, whose node must carry TRS rather than a
// matrix: it keeps Instance::transform exact where TRS could only approximate it. Animated lights'
// and skin joints' nodes carry it alone (their world transform at rest: Light::transform,
// Skin::joints).
#include <optional>

#include <tiny_gltf.h>

#include "scene/gltf_source.h"
#include "scene/scene.h"

namespace strata::scene::gltf {

// `environment_map`: the map's record (export_environment_map), kept as extras.strata.environment_map
// when it is an object.
tinygltf::Value scene_extras(const Scene& scene, const tinygltf::Value& environment_map = {});
tinygltf::Value node_extras(const Instance& instance, bool write_rest_matrix);
// An animated light's or skin joint's node extras: its exact rest transform, world space (TRS alone
// may not compose back to it).
tinygltf::Value rest_matrix_extras(const glm::mat4& rest_matrix);

// Applies extras.strata of `scene_index` to `scene`; false when the file has none.
bool read_scene_extras(const Source& source, int scene_index, Scene& scene);

struct NodeExtras {
  uint32_t lod = 0;
  std::optional<glm::mat4> rest_matrix;
};
NodeExtras read_node_extras(const Source& source, int node);

}  // namespace strata::scene::gltf
