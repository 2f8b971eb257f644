// LDR-FLIP: colour-space round trips, the CSF and feature filters, and error values computed by
// hand for uniform image pairs (where the CSF filtering is the identity and there are no features).
#include <cmath>
#include <numbers>
#include <numeric>

#include <gtest/gtest.h>

#include "metrics/flip_colour.h"
#include "metrics/flip_internal.h"
#include "metrics/metrics.h"
#include "metrics_test_util.h"

namespace strata::metrics {
namespace {

using testing::gray;
using testing::noise;
using testing::uniform;

double sum(const std::vector<float>& v) { return std::accumulate(v.begin(), v.end(), 0.0); }

// c_max by hand from the published CIELAB (D65) values of the sRGB primaries:
//   green (0,1,0): L 87.737, a -86.185, b  83.181  -> Hunt: a' = 0.87737 * -86.185 = -75.616,
//                                                           b' = 0.87737 *  83.181 =  72.981
//   blue  (0,0,1): L 32.303, a  79.197, b -107.864 -> Hunt: a' = 0.32303 *  79.197 =  25.583,
//                                                           b' = 0.32303 * -107.864 = -34.843
//   HyAB = |87.737 - 32.303| + hypot(-75.616 - 25.583, 72.981 + 34.843) = 55.434 + 147.876 = 203.31
//   c_max = 203.31^0.7 = 41.277
double hand_cmax() {
  const double ga = 0.87737 * -86.185, gb = 0.87737 * 83.181, ba = 0.32303 * 79.197, bb = 0.32303 * -107.864;
  return std::pow(std::abs(87.737 - 32.303) + std::hypot(ga - ba, gb - bb), 0.7);
}
// The redistribution of a HyAB distance d: e = d^0.7; e < 0.4 c_max -> 0.95 e / (0.4 c_max), else
// 0.95 + 0.05 (e - 0.4 c_max) / (0.6 c_max).
double hand_remap(double d) {
  const double cmax = hand_cmax(), e = std::pow(d, 0.7), knee = 0.4 * cmax;
  return e < knee ? 0.95 * e / knee : 0.95 + 0.05 * (e - knee) / (cmax - knee);
}
// CIELAB L* of a gray of sRGB value v (a* = b* = 0 for grays): 116 cbrt(linear(v)) - 16 (linear > 0.008856).
double gray_lightness(double v) {
  const double lin = v <= 0.04045 ? v / 12.92 : std::pow((v + 0.055) / 1.055, 2.4);
  return 116.0 * std::cbrt(lin) - 16.0;
}

TEST(FlipColour, MaxColourDistanceMatchesHand) {
  EXPECT_NEAR(hand_cmax(), 41.277, 0.001);
  EXPECT_NEAR(detail::max_colour_distance(), hand_cmax(), 2e-3 * hand_cmax());
}

TEST(FlipColour, WhiteIsTheReferenceWhite) {
  const detail::Color3 w = detail::linear_rgb_to_ycxcz({1.0, 1.0, 1.0});
  EXPECT_NEAR(w[0], 100.0, 1e-12);
  EXPECT_NEAR(w[1], 0.0, 1e-12);
  EXPECT_NEAR(w[2], 0.0, 1e-12);
  // The luminance row of the derived matrix is the familiar Rec. 709 one.
  EXPECT_NEAR(detail::kRgbToXyz[1][0], 0.2126, 1e-4);
  EXPECT_NEAR(detail::kRgbToXyz[1][1], 0.7152, 1e-4);
  EXPECT_NEAR(detail::kRgbToXyz[1][2], 0.0722, 1e-4);
}

TEST(FlipColour, SrgbYcxczRoundTrip) {
  for (double r = 0.0; r <= 1.0; r += 0.125) {
    for (double g = 0.0; g <= 1.0; g += 0.125) {
      for (double b = 0.0; b <= 1.0; b += 0.125) {
        const detail::Color3 back = detail::ycxcz_to_srgb(detail::srgb_to_ycxcz({r, g, b}));
        EXPECT_NEAR(back[0], r, 1e-5);
        EXPECT_NEAR(back[1], g, 1e-5);
        EXPECT_NEAR(back[2], b, 1e-5);
      }
    }
  }
  for (double v : {0.0, 0.001, 0.0031308, 0.04045, 0.2, 0.73, 1.0}) {
    EXPECT_NEAR(detail::srgb_to_linear(detail::linear_to_srgb(v)), v, 1e-12);
  }
}

TEST(FlipColour, LabOfPrimaries) {
  const detail::Color3 g = detail::xyz_to_lab(detail::linear_rgb_to_xyz({0.0, 1.0, 0.0}));
  EXPECT_NEAR(g[0], 87.737, 0.01);
  EXPECT_NEAR(g[1], -86.185, 0.02);
  EXPECT_NEAR(g[2], 83.181, 0.02);
}

TEST(FlipFilters, CsfRadiusAndKernelsSumToOne) {
  // R = ceil(3 sqrt(0.04 / (2 pi^2)) 67) = ceil(3 * 0.0450158 * 67) = ceil(9.048) = 10
  EXPECT_EQ(detail::csf_radius(67.0), 10);
  for (const auto& c : {detail::kCsfAchromatic, detail::kCsfRedGreen, detail::kCsfBlueYellow}) {
    const detail::CsfKernel k = detail::csf_kernel(c, 67.0);
    EXPECT_EQ(k.radius, 10);
    EXPECT_NEAR(k.w[0] + k.w[1], 1.0, 1e-12);
    EXPECT_NEAR(sum(k.g[0]), 1.0, 1e-6);
    if (k.w[1] != 0.0) {
      EXPECT_NEAR(sum(k.g[1]), 1.0, 1e-6);
    }
  }
  EXPECT_EQ(detail::csf_kernel(detail::kCsfAchromatic, 67.0).w[1], 0.0);
  EXPECT_GT(detail::csf_kernel(detail::kCsfBlueYellow, 67.0).w[1], 0.0);
}

TEST(FlipFilters, SeparableBlueYellowKernelIsThePapersTwoDimensionalSum) {
  // s(r) = a1 sqrt(pi/b1) exp(-pi^2 r^2 / b1) + a2 sqrt(pi/b2) exp(-pi^2 r^2 / b2), r in degrees,
  // sampled on the (2R+1)^2 grid and divided by its sum; compare with w0 g0 g0 + w1 g1 g1.
  const double ppd = 30.0, pi = std::numbers::pi;
  const auto c = detail::kCsfBlueYellow;
  const detail::CsfKernel k = detail::csf_kernel(c, ppd);
  const int r = k.radius;
  auto s = [&](int dx, int dy) {
    const double r2 = (dx * dx + dy * dy) / (ppd * ppd);
    return c.a1 * std::sqrt(pi / c.b1) * std::exp(-pi * pi * r2 / c.b1) +
           c.a2 * std::sqrt(pi / c.b2) * std::exp(-pi * pi * r2 / c.b2);
  };
  double total = 0.0;
  for (int y = -r; y <= r; ++y)
    for (int x = -r; x <= r; ++x) total += s(x, y);
  for (auto [x, y] : {std::pair{0, 0}, std::pair{1, 0}, std::pair{2, 3}, std::pair{-4, 1}, std::pair{r, -r}}) {
    const size_t ix = size_t(x + r), iy = size_t(y + r);
    const double separable = k.w[0] * k.g[0][ix] * k.g[0][iy] + k.w[1] * k.g[1][ix] * k.g[1][iy];
    EXPECT_NEAR(separable, s(x, y) / total, 1e-7) << x << "," << y;
  }
}

TEST(FlipFilters, FeatureKernelsNormalization) {
  // sigma = 0.5 * 0.082 * 67 = 2.747 px, radius = ceil(3 sigma) = ceil(8.241) = 9
  const detail::FeatureKernels k = detail::feature_kernels(67.0);
  EXPECT_NEAR(k.sigma, 2.747, 1e-9);
  EXPECT_EQ(k.radius, 9);
  EXPECT_NEAR(sum(k.g), 1.0, 1e-6);
  for (const auto* d : {&k.d1, &k.d2}) {
    double pos = 0.0, neg = 0.0;
    for (float v : *d) (v > 0 ? pos : neg) += v;
    EXPECT_NEAR(pos, 1.0, 1e-6);
    EXPECT_NEAR(neg, -1.0, 1e-6);
  }
  // d1 is odd (an edge detector), d2 even with a negative centre (a point detector).
  EXPECT_NEAR(k.d1[9], 0.0f, 1e-9);
  EXPECT_NEAR(k.d1[8], -k.d1[10], 1e-7);
  EXPECT_LT(k.d2[9], 0.0f);
  EXPECT_NEAR(k.d2[0], k.d2[18], 1e-7);
}

TEST(FlipFilters, UniformPlaneIsUnchanged) {
  detail::Plane p(7, 5);
  std::fill(p.v.begin(), p.v.end(), 42.0f);
  const detail::Plane out = detail::filter_csf(p, detail::csf_kernel(detail::kCsfBlueYellow, 67.0));
  for (float v : out.v) EXPECT_NEAR(v, 42.0f, 1e-4f);
}

TEST(LdrFlip, IdenticalImagesGiveZero) {
  const image::Image img = noise(23, 17, 7);
  const FlipResult r = ldr_flip(img, img);
  EXPECT_EQ(r.mean, 0.0);
  EXPECT_EQ(r.pixels, 23u * 17u);
  ASSERT_EQ(r.error_map.size(), 23u * 17u);
  for (float e : r.error_map) EXPECT_EQ(e, 0.0f);
}

TEST(LdrFlip, BlackVersusWhiteByHand) {
  // Uniform images: the CSFs (which sum to 1) leave them unchanged and there are no features
  // (E_f = 0), so E = E_c. White is L* 100, black L* 0, a* = b* = 0: HyAB = 100.
  // 100^0.7 = 25.119 > 0.4 c_max = 16.511, so E = 0.95 + 0.05 (25.119 - 16.511) / (0.6 * 41.277) = 0.9674.
  const FlipResult r = ldr_flip(gray(16, 16, 0.0f), gray(16, 16, 1.0f));
  const double expected = hand_remap(100.0);
  EXPECT_NEAR(expected, 0.9674, 1e-4);
  EXPECT_NEAR(r.mean, expected, 1e-4);
  for (float e : r.error_map) EXPECT_NEAR(e, expected, 1e-4);
  // Symmetric in test/reference.
  EXPECT_NEAR(ldr_flip(gray(16, 16, 1.0f), gray(16, 16, 0.0f)).mean, expected, 1e-4);
}

TEST(LdrFlip, UniformGraysByHand) {
  // sRGB 0.5 vs 0.6: linear 0.214041 and 0.318547, L* = 116 cbrt(.) - 16 = 53.389 and 63.223,
  // HyAB = 9.8336; 9.8336^0.7 = 4.9534 < 0.4 c_max = 16.511, so E = 0.95 * 4.9534 / 16.511 = 0.2850.
  const double d = gray_lightness(0.6) - gray_lightness(0.5);
  EXPECT_NEAR(d, 9.8336, 1e-4);
  const double expected = hand_remap(d);
  EXPECT_NEAR(expected, 0.2850, 1e-4);
  const FlipResult r = ldr_flip(gray(12, 9, 0.6f), gray(12, 9, 0.5f));
  EXPECT_NEAR(r.mean, expected, 1e-4);
}

TEST(LdrFlip, ValuesOutsideUnitRangeAreClamped) {
  const FlipResult r = ldr_flip(gray(8, 8, 2.0f), gray(8, 8, 1.0f));
  EXPECT_NEAR(r.mean, 0.0, 1e-6);
  EXPECT_NEAR(ldr_flip(gray(8, 8, -1.0f), gray(8, 8, 0.0f)).mean, 0.0, 1e-6);
}

TEST(LdrFlip, LineOnGrayIsLocalized) {
  // A one-pixel dark line on gray vs the same gray: the error is largest on the line, falls off
  // with the CSF blur and the feature filters, and is exactly 0 beyond their radii.
  image::Image test = gray(32, 32, 0.5f);
  for (uint32_t y = 0; y < 32; ++y) testing::set(test, 16, y, 0.2f, 0.2f, 0.2f);
  const FlipResult r = ldr_flip(test, gray(32, 32, 0.5f));
  const float at_line = r.error_map[16 * 32 + 16];
  EXPECT_GT(at_line, 0.0f);
  EXPECT_LE(at_line, 1.0f);
  // Far from the line both images are the same uniform gray.
  EXPECT_NEAR(r.error_map[16 * 32 + 0], 0.0f, 1e-6f);
  // The error decreases away from the line.
  EXPECT_GT(at_line, r.error_map[16 * 32 + 19]);
}

TEST(LdrFlip, MaskRestrictsTheMean) {
  // Left half differs (black vs white), right half identical: the mean over the right half is 0
  // away from the border, and the masked mean equals the plain average of the map over the mask.
  image::Image test = gray(20, 10, 0.5f), ref = gray(20, 10, 0.5f);
  for (uint32_t y = 0; y < 10; ++y)
    for (uint32_t x = 0; x < 10; ++x) testing::set(test, x, y, 0.0f, 0.0f, 0.0f);
  std::vector<uint8_t> right(200, 0), left(200, 0);
  for (uint32_t y = 0; y < 10; ++y)
    for (uint32_t x = 0; x < 20; ++x) (x >= 10 ? right : left)[y * 20 + x] = 1;
  const FlipResult all = ldr_flip(test, ref), r = ldr_flip(test, ref, right), l = ldr_flip(test, ref, left);
  EXPECT_EQ(r.pixels, 100u);
  EXPECT_EQ(l.pixels, 100u);
  double sum_right = 0.0;
  for (size_t i = 0; i < 200; ++i) sum_right += right[i] ? r.error_map[i] : 0.0f;
  EXPECT_NEAR(r.mean, sum_right / 100.0, 1e-9);
  EXPECT_LT(r.mean, l.mean);
  EXPECT_NEAR(all.mean, 0.5 * (r.mean + l.mean), 1e-6);
  EXPECT_EQ(all.error_map, r.error_map);  // the map ignores the mask
}

TEST(LdrFlip, RejectsBadPixelsPerDegree) {
  const image::Image a = gray(2, 2, 0.5f);
  EXPECT_THROW(ldr_flip(a, a, {}, FlipOptions{0.0}), MetricError);
  EXPECT_THROW(ldr_flip(a, a, {}, FlipOptions{std::numeric_limits<double>::quiet_NaN()}), MetricError);
}

}  // namespace
}  // namespace strata::metrics
