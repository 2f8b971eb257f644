#include "scene/normals.h"

#include <cmath>

namespace strata::scene {

std::vector<glm::vec3> area_weighted_normals(std::span<const glm::vec3> positions,
                                             std::span<const uint32_t> indices) {
  std::vector<glm::vec3> sum(positions.size(), glm::vec3(0.0f));
  for (size_t t = 0; t + 2 < indices.size(); t += 3) {
    const glm::vec3& a = positions[indices[t]];
    const glm::vec3& b = positions[indices[t + 1]];
    const glm::vec3& c = positions[indices[t + 2]];
    // The cross product's length is twice the triangle area: that is the weight.
    const glm::vec3 face = glm::cross(b - a, c - a);
    for (size_t k = 0; k < 3; ++k) sum[indices[t + k]] += face;
  }
  for (glm::vec3& n : sum) {
    const float length = glm::length(n);
    n = (length > 0.0f && std::isfinite(length)) ? n / length : glm::vec3(0.0f, 1.0f, 0.0f);
  }
  return sum;
}

}  // namespace strata::scene
