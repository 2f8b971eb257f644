#include "scene/deform.h"

#include <cmath>

namespace strata::scene {

std::vector<SkinningMatrix> skinning_matrices(const Skin& skin, const glm::mat4& instance_transform,
                                              std::span<const glm::mat4> joints) {
  const glm::dmat4 to_object = glm::inverse(glm::dmat4(instance_transform));
  std::vector<SkinningMatrix> out(skin.inverse_bind.size());
  for (size_t j = 0; j < out.size() && j < joints.size(); ++j) {
    const glm::dmat4 s = to_object * glm::dmat4(joints[j]) * glm::dmat4(skin.inverse_bind[j]);
    out[j].position = glm::mat4(s);
    out[j].normal = glm::mat3(glm::transpose(glm::inverse(glm::dmat3(s))));
  }
  return out;
}

std::span<const glm::mat4> joints_at(const Scene& scene, const FrameState& frame, size_t i) {
  if (i < frame.joints.size() && !frame.joints[i].empty()) return frame.joints[i];
  const int32_t skin = scene.instances[i].skin;
  return skin >= 0 ? std::span<const glm::mat4>(scene.skins[size_t(skin)].joints) : std::span<const glm::mat4>();
}

std::span<const float> morph_weights_at(const Scene& scene, const FrameState& frame, size_t i) {
  if (i < frame.morph_weights.size() && !frame.morph_weights[i].empty()) return frame.morph_weights[i];
  return scene.instances[i].morph_weights;
}

std::vector<SkinningMatrix> instance_skinning(const Scene& scene, const FrameState& frame, size_t i) {
  const int32_t skin = scene.instances[i].skin;
  if (skin < 0) return {};
  return skinning_matrices(scene.skins[size_t(skin)], frame.transforms[i], joints_at(scene, frame, i));
}

DeformedVertices deform_primitive(const Primitive& p, std::span<const SkinningMatrix> skinning,
                                  std::span<const float> morph_weights) {
  DeformedVertices out{p.positions, p.normals};
  for (size_t t = 0; t < p.targets.size() && t < morph_weights.size(); ++t) {
    const float w = morph_weights[t];
    if (w == 0.0f) continue;
    const MorphTarget& target = p.targets[t];
    for (size_t v = 0; v < out.positions.size(); ++v) out.positions[v] += w * target.positions[v];
    if (!target.normals.empty())
      for (size_t v = 0; v < out.normals.size(); ++v) out.normals[v] += w * target.normals[v];
  }
  const bool skinned = !skinning.empty() && !p.joints.empty();
  for (size_t v = 0; v < out.positions.size(); ++v) {
    glm::vec3 position = out.positions[v];
    glm::vec3 normal = out.normals[v];
    if (skinned) {
      glm::vec3 ps(0.0f);
      glm::vec3 ns(0.0f);
      for (int k = 0; k < 4; ++k) {
        const float w = p.weights[v][k];
        if (w == 0.0f) continue;
        const SkinningMatrix& m = skinning[p.joints[v][k]];
        ps += w * glm::vec3(m.position * glm::vec4(position, 1.0f));
        ns += w * (m.normal * normal);
      }
      position = ps;
      normal = ns;
    }
    const float len = glm::length(normal);
    out.positions[v] = position;
    out.normals[v] = len > 0.0f && std::isfinite(len) ? normal / len : p.normals[v];
  }
  return out;
}

}  // namespace strata::scene
