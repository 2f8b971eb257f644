#pragma once
// Deforming meshes on the host: the reference the device's deformation pass is tested against
// (shaders/passes/deform.comp), and what the CPU tracer of the tests renders. glTF 2.0's order:
// morph targets first (3.7.2.2: p = p_rest + sum_t w_t dp_t, the same for normals), then the skin
// (3.7.3: p' = sum_j w_j S_j p, normals by the inverse transpose of each S_j, normalised).
#include <span>
#include <vector>

#include <glm/glm.hpp>

#include "scene/scene.h"

namespace strata::scene {

// Joint j's skinning matrix S_j = inverse(T) J_j B_j (scene.h, Skin) in the object space of an
// instance with transform T, and the matrix its normals move by, the inverse transpose of S_j's
// 3 x 3 part; both computed in double precision.
struct SkinningMatrix {
  glm::mat4 position{1.0f};
  glm::mat3 normal{1.0f};
};
std::vector<SkinningMatrix> skinning_matrices(const Skin& skin, const glm::mat4& instance_transform,
                                              std::span<const glm::mat4> joints);

// Instance i's joints (joint to world) and morph weights in `frame`; its rest pose (its skin's
// joints, its own weights) where the frame state has none for it.
std::span<const glm::mat4> joints_at(const Scene& scene, const FrameState& frame, size_t i);
std::span<const float> morph_weights_at(const Scene& scene, const FrameState& frame, size_t i);
// Instance i's skinning matrices in `frame` (empty when it is not skinned).
std::vector<SkinningMatrix> instance_skinning(const Scene& scene, const FrameState& frame, size_t i);

struct DeformedVertices {
  std::vector<glm::vec3> positions;
  std::vector<glm::vec3> normals;  // unit length (the rest normal where the blend degenerates)
};

// A primitive's vertices in its instance's object space, morphed by `morph_weights` (empty: no
// targets) and skinned by `skinning` (empty: not skinned).
DeformedVertices deform_primitive(const Primitive& p, std::span<const SkinningMatrix> skinning,
                                  std::span<const float> morph_weights);

}  // namespace strata::scene
