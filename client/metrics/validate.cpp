// Input checks and masked pooling shared by RelMSE, MAPE, LDR-FLIP and HDR-FLIP.
#include "metrics/validate.h"

#include <cmath>
#include <string>

namespace strata::metrics::detail {
namespace {

std::string size_string(uint32_t width, uint32_t height) {
  return std::to_string(width) + "x" + std::to_string(height);
}

void check_one(const image::Image& img, const char* which) {
  if (img.width == 0 || img.height == 0) {
    throw MetricError(std::string("empty image: ") + which + " is " + size_string(img.width, img.height) +
                      ", expected at least 1x1");
  }
  const size_t expected = 4 * size_t(img.width) * img.height;
  if (img.rgba.size() != expected) {
    throw MetricError(std::string(which) + ".rgba has " + std::to_string(img.rgba.size()) +
                      " floats, expected 4*width*height = " + std::to_string(expected) + " for " +
                      size_string(img.width, img.height));
  }
}

}  // namespace

void check_images(const image::Image& test, const image::Image& reference) {
  check_one(test, "test");
  check_one(reference, "reference");
  if (test.width != reference.width || test.height != reference.height) {
    throw MetricError("size mismatch: test is " + size_string(test.width, test.height) +
                      ", expected the reference size " + size_string(reference.width, reference.height));
  }
}

void check_mask(Mask mask, uint32_t width, uint32_t height) {
  const size_t expected = size_t(width) * height;
  if (!mask.empty() && mask.size() != expected) {
    throw MetricError("mask has " + std::to_string(mask.size()) + " bytes, expected width*height = " +
                      std::to_string(expected) + " (" + size_string(width, height) + ")");
  }
}

void check_finite(const image::Image& img, const char* which) {
  static constexpr char kChannel[3] = {'R', 'G', 'B'};
  for (uint32_t y = 0; y < img.height; ++y) {
    for (uint32_t x = 0; x < img.width; ++x) {
      const float* p = img.pixel(x, y);
      for (int c = 0; c < 3; ++c) {
        if (!std::isfinite(p[c])) {
          throw MetricError(std::string("non-finite value ") + std::to_string(p[c]) + " in " + which +
                            " image at pixel (" + std::to_string(x) + "," + std::to_string(y) + "), channel " +
                            kChannel[c]);
        }
      }
    }
  }
}

void check_inputs(const image::Image& test, const image::Image& reference, Mask mask) {
  check_images(test, reference);
  check_mask(mask, reference.width, reference.height);
  check_finite(test, "test");
  check_finite(reference, "reference");
}

Pooled masked_mean(std::span<const float> values, Mask mask) {
  Pooled out;
  double sum = 0.0;
  for (size_t i = 0; i < values.size(); ++i) {
    if (mask.empty() || mask[i] != 0) {
      sum += values[i];
      ++out.pixels;
    }
  }
  out.mean = out.pixels > 0 ? sum / double(out.pixels) : 0.0;
  return out;
}

}  // namespace strata::metrics::detail
