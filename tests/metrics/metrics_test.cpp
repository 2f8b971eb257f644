// RelMSE and MAPE against hand-computed values, masks, eps, and the input errors shared by every
// metric (size mismatch, empty images, mask length, non-finite pixels).
#include <cmath>
#include <limits>

#include <gtest/gtest.h>

#include "metrics/metrics.h"
#include "metrics_test_util.h"

namespace strata::metrics {
namespace {

using testing::contains;
using testing::gray;
using testing::metric_error_of;
using testing::set;

// The 2x2 pair used below (pixel index = y*2 + x):
//   pixel   reference        test
//   0 (0,0) (1, 1, 1)        (1.5, 1, 1)
//   1 (1,0) (2, 2, 2)        (2, 2, 2)
//   2 (0,1) (0, 0, 0)        (0.1, 0, 0)
//   3 (1,1) (0.5, 0.5, 0.5)  (0.5, 0.5, 1.0)
struct Pair {
  image::Image test, reference;
};
Pair two_by_two() {
  Pair p{gray(2, 2, 0.0f), gray(2, 2, 0.0f)};
  set(p.reference, 0, 0, 1.0f, 1.0f, 1.0f);
  set(p.reference, 1, 0, 2.0f, 2.0f, 2.0f);
  set(p.reference, 0, 1, 0.0f, 0.0f, 0.0f);
  set(p.reference, 1, 1, 0.5f, 0.5f, 0.5f);
  set(p.test, 0, 0, 1.5f, 1.0f, 1.0f);
  set(p.test, 1, 0, 2.0f, 2.0f, 2.0f);
  set(p.test, 0, 1, 0.1f, 0.0f, 0.0f);
  set(p.test, 1, 1, 0.5f, 0.5f, 1.0f);
  return p;
}

TEST(RelMse, TwoByTwoByHand) {
  const Pair p = two_by_two();
  // eps = 0.01; only three of the 12 channel terms are non-zero:
  //   pixel 0 R: (1.5 - 1)^2 / (1^2 + 0.01)     = 0.25 / 1.01 = 0.2475247525
  //   pixel 2 R: (0.1 - 0)^2 / (0^2 + 0.01)     = 0.01 / 0.01 = 1
  //   pixel 3 B: (1 - 0.5)^2 / (0.5^2 + 0.01)   = 0.25 / 0.26 = 0.9615384615
  // sum = 2.2090632140, mean over 4 pixels x 3 channels = 2.2090632140 / 12 = 0.1840886012
  const double expected = (0.25 / 1.01 + 1.0 + 0.25 / 0.26) / 12.0;
  EXPECT_NEAR(relmse(p.test, p.reference), expected, 1e-6);  // the float 0.1 gives ~1e-8 slack
  EXPECT_NEAR(expected, 0.1840886012, 1e-9);
}

TEST(RelMse, MaskSelectsPixels) {
  const Pair p = two_by_two();
  // Pixels 0 and 2: (0.2475247525 + 1) / (2 pixels x 3 channels) = 0.2079207921
  const uint8_t mask[4] = {1, 0, 7, 0};  // any non-zero byte selects
  EXPECT_NEAR(relmse(p.test, p.reference, mask), (0.25 / 1.01 + 1.0) / 6.0, 1e-6);
  // Pixel 1 alone is exact: 0.
  const uint8_t only_equal[4] = {0, 1, 0, 0};
  EXPECT_EQ(relmse(p.test, p.reference, only_equal), 0.0);
}

TEST(RelMse, EpsControlsTheBlackReferenceTerm) {
  // One pixel, reference 0, test (0.1, 0, 0): (0.1)^2 / (0 + eps) / 3 channels.
  image::Image ref = gray(1, 1, 0.0f), test = gray(1, 1, 0.0f);
  set(test, 0, 0, 0.1f, 0.0f, 0.0f);
  const double d2 = double(0.1f) * double(0.1f);
  EXPECT_NEAR(relmse(test, ref, {}, 1e-2), d2 / 1e-2 / 3.0, 1e-12);  // = 0.3333
  EXPECT_NEAR(relmse(test, ref, {}, 1.0), d2 / 1.0 / 3.0, 1e-12);    // = 0.003333
  EXPECT_TRUE(contains(metric_error_of([&] { relmse(test, ref, {}, 0.0); }), "eps"));
  EXPECT_TRUE(contains(metric_error_of([&] { relmse(test, ref, {}, -1.0); }), "eps"));
}

// The luminance RelMSE sees a brightness error and not a pure hue error: on the 2x2 pair pixel 0's
// red +0.5 is a luminance error of 0.2126 * 0.5, pixel 2's 0.1 of 0.02126 (reference 0), pixel 3's
// blue +0.5 of 0.0722 * 0.5; and a test that swaps luminance between channels at equal Y scores 0.
TEST(RelMseLuminance, TwoByTwoByHandAndHueAlone) {
  const Pair p = two_by_two();
  const double d0 = 0.2126 * 0.5, d2 = 0.2126 * 0.1, d3 = 0.0722 * 0.5;
  const double expected = (d0 * d0 / (1.0 + 1e-2) + d2 * d2 / 1e-2 + d3 * d3 / (0.25 + 1e-2)) / 4.0;
  EXPECT_NEAR(relmse_luminance(p.test, p.reference), expected, 1e-7);

  image::Image ref = gray(1, 1, 1.0f), hue = gray(1, 1, 0.0f);
  set(hue, 0, 0, 1.0f / 0.2126f, 0.0f, 0.0f);  // all red, same luminance as the grey reference
  EXPECT_NEAR(relmse_luminance(hue, ref), 0.0, 1e-10);
  EXPECT_GT(relmse(hue, ref), 1.0);
  EXPECT_TRUE(contains(metric_error_of([&] { relmse_luminance(hue, ref, {}, 0.0); }), "eps"));
}

TEST(Mape, TwoByTwoByHand) {
  const Pair p = two_by_two();
  // eps = 0.01:
  //   pixel 0 R: |1.5 - 1| / (1 + 0.01)   = 0.5 / 1.01 = 0.4950495050
  //   pixel 2 R: |0.1 - 0| / (0 + 0.01)   = 0.1 / 0.01 = 10
  //   pixel 3 B: |1 - 0.5| / (0.5 + 0.01) = 0.5 / 0.51 = 0.9803921569
  // sum = 11.4754416619, / 12 = 0.9562868052
  EXPECT_NEAR(mape(p.test, p.reference), (0.5 / 1.01 + 10.0 + 0.5 / 0.51) / 12.0, 1e-5);
  // Mask: pixel 3 only: 0.9803921569 / 3 = 0.3267973856
  const uint8_t mask[4] = {0, 0, 0, 1};
  EXPECT_NEAR(mape(p.test, p.reference, mask), 0.5 / 0.51 / 3.0, 1e-7);
}

TEST(Mape, NegativeReferenceUsesItsMagnitude) {
  // |1 - (-1)| / (|-1| + 0.5) = 2 / 1.5 on every channel.
  image::Image ref = gray(1, 1, -1.0f), test = gray(1, 1, 1.0f);
  EXPECT_NEAR(mape(test, ref, {}, 0.5), 2.0 / 1.5, 1e-12);
}

TEST(Metrics, AllZeroMaskGivesZeroNotNaN) {
  const Pair p = two_by_two();
  const uint8_t none[4] = {0, 0, 0, 0};
  EXPECT_EQ(relmse(p.test, p.reference, none), 0.0);
  EXPECT_EQ(mape(p.test, p.reference, none), 0.0);
  const FlipResult f = ldr_flip(p.test, p.reference, none);
  EXPECT_EQ(f.mean, 0.0);
  EXPECT_EQ(f.pixels, 0u);
  EXPECT_EQ(f.error_map.size(), 4u);  // the map is still of the whole image
  const HdrFlipResult h = hdr_flip(p.test, p.reference, none);
  EXPECT_EQ(h.mean, 0.0);
  EXPECT_EQ(h.pixels, 0u);
}

TEST(MetricErrors, SizeMismatchNamesBothSizes) {
  const image::Image a = gray(3, 2, 0.5f), b = gray(2, 2, 0.5f);
  for (const std::string& m : {metric_error_of([&] { relmse(a, b); }), metric_error_of([&] { mape(a, b); }),
                               metric_error_of([&] { ldr_flip(a, b); }), metric_error_of([&] { hdr_flip(a, b); })}) {
    EXPECT_TRUE(contains(m, "test is 3x2")) << m;
    EXPECT_TRUE(contains(m, "2x2")) << m;
  }
}

TEST(MetricErrors, EmptyImage) {
  const image::Image empty{}, one = gray(1, 1, 0.5f);
  const std::string m = metric_error_of([&] { relmse(empty, one); });
  EXPECT_TRUE(contains(m, "empty")) << m;
  EXPECT_TRUE(contains(m, "test is 0x0")) << m;
  const std::string r = metric_error_of([&] { ldr_flip(one, empty); });
  EXPECT_TRUE(contains(r, "reference is 0x0")) << r;
}

TEST(MetricErrors, RgbaLengthMustMatchTheSize) {
  image::Image bad = gray(2, 2, 0.5f);
  bad.rgba.resize(15);
  const std::string m = metric_error_of([&] { mape(gray(2, 2, 0.5f), bad); });
  EXPECT_TRUE(contains(m, "reference.rgba has 15 floats")) << m;
  EXPECT_TRUE(contains(m, "16")) << m;
}

TEST(MetricErrors, MaskOfWrongLength) {
  const image::Image a = gray(2, 2, 0.5f);
  const uint8_t mask[3] = {1, 1, 1};
  for (const std::string& m :
       {metric_error_of([&] { relmse(a, a, mask); }), metric_error_of([&] { ldr_flip(a, a, mask); }),
        metric_error_of([&] { hdr_flip(a, a, mask); })}) {
    EXPECT_TRUE(contains(m, "mask has 3 bytes")) << m;
    EXPECT_TRUE(contains(m, "width*height = 4")) << m;
  }
}

TEST(MetricErrors, NonFinitePixelIsNamed) {
  const image::Image ok = gray(4, 4, 0.5f);
  image::Image nan_test = ok, inf_ref = ok;
  nan_test.pixel(2, 1)[1] = std::numeric_limits<float>::quiet_NaN();
  inf_ref.pixel(0, 3)[2] = std::numeric_limits<float>::infinity();
  const std::string m = metric_error_of([&] { relmse(nan_test, ok); });
  EXPECT_TRUE(contains(m, "test image at pixel (2,1)")) << m;
  const std::string r = metric_error_of([&] { mape(ok, inf_ref); });
  EXPECT_TRUE(contains(r, "reference image at pixel (0,3)")) << r;
  // Alpha is ignored.
  image::Image nan_alpha = ok;
  nan_alpha.pixel(1, 1)[3] = std::numeric_limits<float>::quiet_NaN();
  EXPECT_EQ(relmse(nan_alpha, ok), 0.0);
}

}  // namespace
}  // namespace strata::metrics
