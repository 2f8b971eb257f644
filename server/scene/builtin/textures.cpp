#include "scene/builtin/textures.h"

#include <glm/glm.hpp>

#include "scene/builtin/random.h"

namespace strata::scene::builtin {

int32_t leaf_texture(Scene& s) {
  return add_generated(s, "leaf", 32, 32, ColorSpace::kSrgb, [](uint32_t x, uint32_t y) {
    const glm::vec2 p = (glm::vec2(float(x), float(y)) + 0.5f) / 32.0f;
    for (const glm::vec2 c : {glm::vec2(0.32f, 0.4f), glm::vec2(0.68f, 0.62f)}) {
      const glm::vec2 d = (p - c) / glm::vec2(0.16f, 0.3f);
      if (glm::dot(d, d) <= 1.0f) {
        const float vein = std::abs(p.x - c.x) < 0.02f ? 0.6f : 1.0f;
        return rgba(0.18f * vein, 0.42f * vein, 0.1f * vein, 1.0f);
      }
    }
    return rgba(0.18f, 0.42f, 0.1f, 0.0f);
  });
}

float tiled_noise(uint32_t x, uint32_t y, uint32_t cell, uint32_t period, uint32_t seed) {
  const uint32_t cells = period / cell;
  auto value = [&](uint32_t i, uint32_t j) {
    return float(hash2(int32_t(i % cells), int32_t(j % cells), seed) >> 8) / 16777216.0f;
  };
  const uint32_t i = x / cell, j = y / cell;
  const float fx = (float(x % cell) + 0.5f) / float(cell), fy = (float(y % cell) + 0.5f) / float(cell);
  const float top = value(i, j) + (value(i + 1, j) - value(i, j)) * fx;
  const float bottom = value(i, j + 1) + (value(i + 1, j + 1) - value(i, j + 1)) * fx;
  return top + (bottom - top) * fy;
}

}  // namespace strata::scene::builtin
