#pragma once
// Small image builders and an exception-message helper for the metrics tests.
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "metrics/metrics.h"

namespace strata::metrics::testing {

// width x height, every pixel (r, g, b, 1).
inline image::Image uniform(uint32_t width, uint32_t height, float r, float g, float b) {
  image::Image img{width, height, std::vector<float>(4 * size_t(width) * height)};
  for (size_t i = 0; i < size_t(width) * height; ++i) {
    img.rgba[4 * i + 0] = r;
    img.rgba[4 * i + 1] = g;
    img.rgba[4 * i + 2] = b;
    img.rgba[4 * i + 3] = 1.0f;
  }
  return img;
}
inline image::Image gray(uint32_t width, uint32_t height, float v) { return uniform(width, height, v, v, v); }

inline void set(image::Image& img, uint32_t x, uint32_t y, float r, float g, float b) {
  float* p = img.pixel(x, y);
  p[0] = r;
  p[1] = g;
  p[2] = b;
}

// Deterministic pseudo-random values in [0, scale) (a 32-bit LCG), alpha 1.
inline image::Image noise(uint32_t width, uint32_t height, uint32_t seed, float scale = 1.0f) {
  image::Image img = gray(width, height, 0.0f);
  uint32_t s = seed;
  for (size_t i = 0; i < size_t(width) * height; ++i) {
    for (int c = 0; c < 3; ++c) {
      s = s * 1664525u + 1013904223u;
      img.rgba[4 * i + c] = scale * float(s >> 8) / float(1u << 24);
    }
  }
  return img;
}

// Runs f, expects a MetricError, and returns its message.
template <typename F>
std::string metric_error_of(F&& f) {
  try {
    f();
  } catch (const MetricError& e) {
    return e.what();
  } catch (const std::exception& e) {
    ADD_FAILURE() << "wrong exception type: " << e.what();
    return {};
  }
  ADD_FAILURE() << "no exception";
  return {};
}

inline bool contains(const std::string& haystack, const std::string& needle) {
  return haystack.find(needle) != std::string::npos;
}

}  // namespace strata::metrics::testing
