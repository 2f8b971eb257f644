// HDR-FLIP: the ACES curve, the automatic exposure range against the hand-computed formula, the
// finite-range rules for black references, huge values, explicit ranges and masks.
#include <cmath>
#include <limits>

#include <gtest/gtest.h>

#include "metrics/flip_colour.h"
#include "metrics/flip_internal.h"
#include "metrics/metrics.h"
#include "metrics_test_util.h"

namespace strata::metrics {
namespace {

using testing::contains;
using testing::gray;
using testing::metric_error_of;
using testing::noise;
using testing::set;

// x85: the exposed radiance that ACES maps to 0.85. With y = 0.6 x, Narkowicz's
// y (2.51 y + 0.03) / (y (2.43 y + 0.59) + 0.14) = 0.85 gives
//   (2.51 - 0.85 * 2.43) y^2 + (0.03 - 0.85 * 0.59) y - 0.85 * 0.14 = 0
//   0.4445 y^2 - 0.4715 y - 0.119 = 0  ->  y = (0.4715 + sqrt(0.4715^2 + 4 * 0.4445 * 0.119)) / 0.889
//                                          = (0.4715 + 0.6587) / 0.889 = 1.2713,  x85 = y / 0.6 = 2.1189
double hand_x85() {
  const double a = 2.51 - 0.85 * 2.43, b = 0.03 - 0.85 * 0.59, c = -0.85 * 0.14;
  return (-b + std::sqrt(b * b - 4 * a * c)) / (2 * a) / 0.6;
}

TEST(HdrFlipAces, CurveAndInverse) {
  EXPECT_NEAR(hand_x85(), 2.1189, 1e-3);
  EXPECT_NEAR(detail::aces_input_for(0.85), hand_x85(), 1e-12);
  EXPECT_NEAR(detail::aces_tonemap(hand_x85()), 0.85, 1e-12);
  EXPECT_EQ(detail::aces_tonemap(0.0), 0.0);
  EXPECT_EQ(detail::aces_tonemap(-3.0), 0.0);
  // y = 0.6: 0.6 (1.506 + 0.03) / (0.6 (1.458 + 0.59) + 0.14) = 0.9216 / 1.3688 = 0.67329
  EXPECT_NEAR(detail::aces_tonemap(1.0), 0.9216 / 1.3688, 1e-12);
  // Continuous across the y = 1 switch of formulation, saturating at 1 for huge inputs.
  EXPECT_NEAR(detail::aces_tonemap(1.0 / 0.6 - 1e-12), detail::aces_tonemap(1.0 / 0.6 + 1e-12), 1e-9);
  EXPECT_EQ(detail::aces_tonemap(1e300), 1.0);
  EXPECT_EQ(detail::aces_tonemap(double(std::numeric_limits<float>::max()) * 1e100), 1.0);
}

TEST(HdrFlipRange, ConstantLuminanceReference) {
  // Y_max = Y_median = 0.5: start = stop = log2(x85 / 0.5) = log2(4.2378) = 2.0833; N = max(2, 0) = 2.
  const image::Image ref = gray(8, 8, 0.5f);
  const HdrFlipResult r = hdr_flip(ref, ref);
  EXPECT_NEAR(r.start_exposure, std::log2(hand_x85() / 0.5), 1e-9);
  EXPECT_NEAR(r.stop_exposure, r.start_exposure, 1e-12);
  EXPECT_EQ(r.exposures, 2u);
  EXPECT_EQ(r.mean, 0.0);
}

TEST(HdrFlipRange, MaxAndMedianByHand) {
  // Luminances {1, 1, 1, 16} (grays): max 16, upper median (index 4/2 = 2 of the sorted values) 1.
  // start = log2(x85 / 16), stop = log2(x85 / 1): 4 stops apart, N = ceil(4) = 4 exposures.
  image::Image ref = gray(4, 1, 1.0f);
  set(ref, 3, 0, 16.0f, 16.0f, 16.0f);
  const HdrFlipResult r = hdr_flip(ref, ref);
  EXPECT_NEAR(r.start_exposure, std::log2(hand_x85() / 16.0), 1e-9);
  EXPECT_NEAR(r.stop_exposure, std::log2(hand_x85()), 1e-9);
  EXPECT_EQ(r.exposures, 4u);
  // Colour: luminance 0.2126 R + 0.7152 G + 0.0722 B. A pure green pixel of 2: Y = 1.4304.
  image::Image green = gray(1, 1, 0.0f);
  set(green, 0, 0, 0.0f, 2.0f, 0.0f);
  EXPECT_NEAR(detail::automatic_exposure_range(green).start, std::log2(hand_x85() / 1.4304), 1e-6);
}

TEST(HdrFlipRange, BlackReferenceIsFinite) {
  // All black: no scale; the documented rule gives start = stop = 0.
  const image::Image black = gray(16, 16, 0.0f);
  const image::Image test = noise(16, 16, 3, 0.01f);
  const HdrFlipResult r = hdr_flip(test, black);
  EXPECT_EQ(r.start_exposure, 0.0);
  EXPECT_EQ(r.stop_exposure, 0.0);
  EXPECT_EQ(r.exposures, 2u);
  EXPECT_TRUE(std::isfinite(r.mean));
  EXPECT_GT(r.mean, 0.0);
  EXPECT_LE(r.mean, 1.0);
  for (float e : r.error_map) EXPECT_TRUE(std::isfinite(e) && e >= 0.0f && e <= 1.0f);
  EXPECT_EQ(hdr_flip(black, black).mean, 0.0);
  // Below the black threshold counts as black too.
  EXPECT_EQ(detail::automatic_exposure_range(gray(4, 4, 1e-12f)).start, 0.0);
}

TEST(HdrFlipRange, MostlyBlackReferenceUsesTheLitMedian) {
  // Luminances {0, 0, 0, 0, 2, 4, 8}: the upper median (index 3) is black, so the median of the lit
  // pixels {2, 4, 8} (index 1) = 4 is used: start = log2(x85 / 8), stop = log2(x85 / 4), N = 2.
  image::Image ref = gray(7, 1, 0.0f);
  set(ref, 4, 0, 2.0f, 2.0f, 2.0f);
  set(ref, 5, 0, 4.0f, 4.0f, 4.0f);
  set(ref, 6, 0, 8.0f, 8.0f, 8.0f);
  const HdrFlipResult r = hdr_flip(ref, ref);
  EXPECT_NEAR(r.start_exposure, std::log2(hand_x85() / 8.0), 1e-9);
  EXPECT_NEAR(r.stop_exposure, std::log2(hand_x85() / 4.0), 1e-9);
  EXPECT_EQ(r.exposures, 2u);
}

TEST(HdrFlipRange, AutomaticRangeIsCapped) {
  // max 1e6, median 1e-3: log2(1e9) = 29.9 stops, capped at kHdrFlipMaxAutoRange = 20.
  image::Image ref = gray(3, 1, 1e-3f);
  set(ref, 2, 0, 1e6f, 1e6f, 1e6f);
  const detail::ExposureRange r = detail::automatic_exposure_range(ref);
  EXPECT_NEAR(r.start, std::log2(hand_x85() / 1e6), 1e-6);
  EXPECT_NEAR(r.stop - r.start, kHdrFlipMaxAutoRange, 1e-12);
}

TEST(HdrFlip, HugeValuesGiveNoNaN) {
  // A test pixel at FLT_MAX (and a reference pixel at 1e30) must tone-map to 1, not inf/inf.
  image::Image ref = noise(12, 12, 5, 2.0f), test = ref;
  set(test, 3, 4, std::numeric_limits<float>::max(), 1e30f, 0.0f);
  set(ref, 8, 8, 1e30f, 1e30f, 1e30f);
  const HdrFlipResult r = hdr_flip(test, ref);
  EXPECT_TRUE(std::isfinite(r.start_exposure));
  EXPECT_TRUE(std::isfinite(r.stop_exposure));
  EXPECT_TRUE(std::isfinite(r.mean));
  for (float e : r.error_map) EXPECT_TRUE(std::isfinite(e) && e >= 0.0f && e <= 1.0f);
  EXPECT_GT(r.error_map[4 * 12 + 3], 0.5f);
  // The same with the scale applied to the whole pair: finite, and the range follows the scale.
  image::Image big_ref = ref, big_test = test;
  for (float& v : big_ref.rgba) v *= 1e8f;
  for (float& v : big_test.rgba) v = std::isinf(v * 1e8f) ? std::numeric_limits<float>::max() : v * 1e8f;
  const HdrFlipResult big = hdr_flip(big_test, big_ref);
  EXPECT_TRUE(std::isfinite(big.mean));
}

TEST(HdrFlip, NonFinitePixelIsNamed) {
  const image::Image ok = gray(4, 4, 0.5f);
  image::Image bad = ok;
  bad.pixel(2, 1)[0] = std::numeric_limits<float>::quiet_NaN();
  std::string m = metric_error_of([&] { hdr_flip(bad, ok); });
  EXPECT_TRUE(contains(m, "test image at pixel (2,1)")) << m;
  bad = ok;
  bad.pixel(3, 0)[2] = -std::numeric_limits<float>::infinity();
  m = metric_error_of([&] { hdr_flip(ok, bad); });
  EXPECT_TRUE(contains(m, "reference image at pixel (3,0)")) << m;
}

TEST(HdrFlip, SingleExposureEqualsLdrFlipOfTheToneMappedPair) {
  // start = stop = e: HDR-FLIP is LDR-FLIP of ACES(2^e x), which ldr_flip takes sRGB-encoded.
  const image::Image ref = noise(24, 20, 11, 3.0f), test = noise(24, 20, 12, 3.0f);
  const double e = -0.5;
  HdrFlipOptions opt;
  opt.start_exposure = opt.stop_exposure = e;
  const HdrFlipResult h = hdr_flip(test, ref, {}, opt);
  EXPECT_EQ(h.exposures, 2u);
  auto encode = [e](const image::Image& img) {
    image::Image out = img;
    for (size_t i = 0; i < out.rgba.size(); ++i) {
      if (i % 4 != 3) out.rgba[i] = float(detail::linear_to_srgb(detail::aces_tonemap(std::exp2(e) * img.rgba[i])));
    }
    return out;
  };
  const FlipResult l = ldr_flip(encode(test), encode(ref));
  ASSERT_EQ(l.error_map.size(), h.error_map.size());
  for (size_t i = 0; i < l.error_map.size(); ++i) EXPECT_NEAR(h.error_map[i], l.error_map[i], 2e-4) << i;
  EXPECT_NEAR(h.mean, l.mean, 1e-5);
}

TEST(HdrFlip, MaxOverExposuresIsAtLeastEachExposure) {
  const image::Image ref = noise(16, 16, 21, 4.0f), test = noise(16, 16, 22, 4.0f);
  const HdrFlipResult all = hdr_flip(test, ref);
  ASSERT_GE(all.exposures, 2u);
  const double step = (all.stop_exposure - all.start_exposure) / (all.exposures - 1);
  for (uint32_t k = 0; k < all.exposures; ++k) {
    HdrFlipOptions one;
    one.start_exposure = one.stop_exposure = all.start_exposure + k * step;
    const HdrFlipResult r = hdr_flip(test, ref, {}, one);
    for (size_t i = 0; i < r.error_map.size(); ++i) EXPECT_GE(all.error_map[i], r.error_map[i] - 1e-6f);
  }
}

TEST(HdrFlip, ExplicitRange) {
  const image::Image ref = gray(4, 4, 1.0f);
  HdrFlipOptions opt;
  opt.start_exposure = -3.0;
  opt.stop_exposure = 2.5;  // 5.5 stops: N = ceil(5.5) = 6
  HdrFlipResult r = hdr_flip(ref, ref, {}, opt);
  EXPECT_EQ(r.start_exposure, -3.0);
  EXPECT_EQ(r.stop_exposure, 2.5);
  EXPECT_EQ(r.exposures, 6u);
  // Only one given: the other is automatic (stop = log2(x85 / 1) = 1.0833).
  HdrFlipOptions half;
  half.start_exposure = -3.0;
  r = hdr_flip(ref, ref, {}, half);
  EXPECT_NEAR(r.stop_exposure, std::log2(hand_x85()), 1e-9);
  EXPECT_EQ(r.exposures, 5u);  // ceil(4.0833)
  // Invalid ranges.
  HdrFlipOptions reversed;
  reversed.start_exposure = 1.0;
  reversed.stop_exposure = 0.0;
  EXPECT_TRUE(contains(metric_error_of([&] { hdr_flip(ref, ref, {}, reversed); }), "start_exposure"));
  HdrFlipOptions infinite;
  infinite.stop_exposure = std::numeric_limits<double>::infinity();
  EXPECT_TRUE(contains(metric_error_of([&] { hdr_flip(ref, ref, {}, infinite); }), "stop_exposure"));
  HdrFlipOptions too_wide;
  too_wide.start_exposure = -50.0;
  too_wide.stop_exposure = 50.0;
  EXPECT_TRUE(contains(metric_error_of([&] { hdr_flip(ref, ref, {}, too_wide); }), "exceeds"));
}

TEST(HdrFlip, MaskRestrictsTheMean) {
  // The top half differs (test 4x brighter), the bottom half is identical and far enough from the
  // boundary (rows 0-3 vs 14-17 of an 18-row image, filter radii <= 10) to have zero error.
  image::Image ref = gray(16, 18, 0.3f), test = ref;
  for (uint32_t y = 0; y < 4; ++y)
    for (uint32_t x = 0; x < 16; ++x) set(test, x, y, 1.2f, 1.2f, 1.2f);
  std::vector<uint8_t> bottom(16 * 18, 0), top(16 * 18, 0);
  for (uint32_t x = 0; x < 16; ++x) {
    for (uint32_t y = 14; y < 18; ++y) bottom[y * 16 + x] = 1;
    for (uint32_t y = 0; y < 4; ++y) top[y * 16 + x] = 1;
  }
  const HdrFlipResult b = hdr_flip(test, ref, bottom), t = hdr_flip(test, ref, top), all = hdr_flip(test, ref);
  EXPECT_EQ(b.pixels, 64u);
  EXPECT_EQ(b.mean, 0.0);
  EXPECT_GT(t.mean, 0.1);
  EXPECT_GT(t.mean, all.mean);
  EXPECT_EQ(all.pixels, 16u * 18u);
}

}  // namespace
}  // namespace strata::metrics
