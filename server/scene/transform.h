#pragma once
// Translation/rotation/scale transforms. Animation sampling, the glTF loader and the exporter all
// compose and decompose through these two functions, so that a key written and read back gives
// the same matrix bit for bit.
#include <glm/glm.hpp>
#include <glm/gtc/quaternion.hpp>

#include "scene/scene.h"

namespace strata::scene {

// T * R * S as one matrix (glTF node order).
glm::mat4 compose_trs(const glm::vec3& translation, const glm::quat& rotation,
                      const glm::vec3& scale);
glm::mat4 compose_trs(const TransformKey& key);

// Splits an affine matrix into translation, unit rotation and scale; a mirroring matrix gets a
// negative x scale. `time` of the result is 0. Zero-scale axes give an identity rotation.
TransformKey decompose_trs(const glm::mat4& matrix);

}  // namespace strata::scene
