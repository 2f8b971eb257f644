// LDR-FLIP and HDR-FLIP on a small deterministic pair against the values that NVIDIA's FLIP C++
// reference (github.com/NVlabs/flip, src/cpp/FLIP.h at commit 1eb247c, PPD 67) gives for the same
// inputs: an independent check of the constants, filters and exposure range. The reference takes
// linear RGB for LDR-FLIP, so it was fed srgb_to_linear of the images below; it computes in float and
// approximates the blue-yellow CSF by separated convolutions, hence the 2e-4 tolerance.
#include <algorithm>
#include <cmath>

#include <gtest/gtest.h>

#include "metrics/flip_colour.h"
#include "metrics/metrics.h"
#include "metrics_test_util.h"

namespace strata::metrics {
namespace {

constexpr uint32_t kW = 40, kH = 30;

// Reference: sinusoids in R and G, a 6-pixel checkerboard in B (sRGB values in [0.1, 0.9]).
image::Image pattern() {
  image::Image img = testing::gray(kW, kH, 0.0f);
  for (uint32_t y = 0; y < kH; ++y) {
    for (uint32_t x = 0; x < kW; ++x) {
      testing::set(img, x, y, 0.5f + 0.4f * std::sin(0.3f * float(x)), 0.5f + 0.4f * std::cos(0.2f * float(y)),
                   ((x / 6 + y / 6) % 2) ? 0.9f : 0.1f);
    }
  }
  return img;
}

// Test: the reference plus uniform noise in [-0.15, 0.15), clamped to [0, 1].
image::Image noisy(const image::Image& ref) {
  const image::Image n = testing::noise(kW, kH, 99);
  image::Image out = ref;
  for (size_t i = 0; i < out.rgba.size(); ++i) {
    if (i % 4 != 3) out.rgba[i] = std::clamp(ref.rgba[i] + 0.3f * (n.rgba[i] - 0.5f), 0.0f, 1.0f);
  }
  return out;
}

// HDR version: linear values times 2^(x/5 - 3), a ramp over 8 stops across the image.
image::Image hdr(const image::Image& srgb) {
  image::Image out = srgb;
  for (uint32_t y = 0; y < kH; ++y) {
    for (uint32_t x = 0; x < kW; ++x) {
      const float s = std::exp2(float(x) / 5.0f - 3.0f);
      for (int c = 0; c < 3; ++c) out.pixel(x, y)[c] = float(detail::srgb_to_linear(srgb.pixel(x, y)[c])) * s;
    }
  }
  return out;
}

TEST(FlipReferenceValues, LdrMean) {
  const image::Image ref = pattern(), test = noisy(ref);
  EXPECT_NEAR(ldr_flip(test, ref).mean, 0.153914, 2e-4);
}

TEST(FlipReferenceValues, HdrMeanAndRange) {
  const image::Image ref = pattern(), test = noisy(ref);
  const HdrFlipResult r = hdr_flip(hdr(test), hdr(ref));
  EXPECT_NEAR(r.start_exposure, -2.907269, 1e-4);
  EXPECT_NEAR(r.stop_exposure, 2.437491, 1e-4);
  EXPECT_EQ(r.exposures, 6u);
  EXPECT_NEAR(r.mean, 0.243371, 2e-4);
}

}  // namespace
}  // namespace strata::metrics
