#pragma once
// Click-to-select in the viewer: the instance whose triangles the camera ray through a point of the
// image hits first, tested on the CPU against the scene's meshes at the frame state the viewer last
// sent (each instance's LoD level and transform). Instances whose world bounding box the ray misses
// are skipped before their triangles are.
#include <cstdint>
#include <optional>

#include <glm/glm.hpp>

#include "scene/scene.h"

namespace strata::http {

struct PickHit {
  uint32_t instance = 0;
  float distance = 0.0f;  // along the unit ray from the camera position
  glm::vec3 point{0.0f};
};

// The unit direction of the camera ray through (u, v) of the image, u to the right and v down, both
// in [0, 1]; `aspect` is width / height. The camera looks down its local -Z with +Y up.
glm::vec3 camera_ray(const scene::Camera& camera, float u, float v, float aspect);

std::optional<PickHit> pick_instance(const scene::Scene& scene, const scene::FrameState& state, float u, float v, float aspect);

}  // namespace strata::http
