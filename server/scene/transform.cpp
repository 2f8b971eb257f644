#include "scene/transform.h"

#include <cmath>

namespace strata::scene {

glm::mat4 compose_trs(const glm::vec3& translation, const glm::quat& rotation,
                      const glm::vec3& scale) {
  const glm::mat3 r = glm::mat3_cast(rotation);
  glm::mat4 m(1.0f);
  m[0] = glm::vec4(r[0] * scale.x, 0.0f);
  m[1] = glm::vec4(r[1] * scale.y, 0.0f);
  m[2] = glm::vec4(r[2] * scale.z, 0.0f);
  m[3] = glm::vec4(translation, 1.0f);
  return m;
}

glm::mat4 compose_trs(const TransformKey& key) {
  return compose_trs(key.translation, key.rotation, key.scale);
}

TransformKey decompose_trs(const glm::mat4& matrix) {
  TransformKey key;
  key.translation = glm::vec3(matrix[3]);
  glm::mat3 basis(matrix);
  key.scale = glm::vec3(glm::length(basis[0]), glm::length(basis[1]), glm::length(basis[2]));
  if (glm::determinant(basis) < 0.0f) key.scale.x = -key.scale.x;
  for (int axis = 0; axis < 3; ++axis) {
    if (key.scale[axis] == 0.0f) return key;  // rotation is undefined; keep identity
    basis[axis] /= key.scale[axis];
  }
  key.rotation = glm::normalize(glm::quat_cast(basis));
  return key;
}

}  // namespace strata::scene

namespace strata::scene {

// KHR_texture_transform's matrix: translation * rotation * scale, with the rotation
// [cos sin; -sin cos] as the extension's specification writes it (rows).
glm::mat3 TextureTransform::matrix() const {
  const float c = std::cos(rotation), s = std::sin(rotation);
  const glm::mat3 t(glm::vec3(1, 0, 0), glm::vec3(0, 1, 0), glm::vec3(offset, 1));
  const glm::mat3 r(glm::vec3(c, -s, 0), glm::vec3(s, c, 0), glm::vec3(0, 0, 1));
  const glm::mat3 sc(glm::vec3(scale.x, 0, 0), glm::vec3(0, scale.y, 0), glm::vec3(0, 0, 1));
  return t * r * sc;
}

}  // namespace strata::scene
