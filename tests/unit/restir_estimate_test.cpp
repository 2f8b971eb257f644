// The pixel estimate over all candidates (restir/gris.h, gris_stream_path) against the selected
// sample's f(Y) W_Y, in a 1D model with a colour integrand: pixel value = integral over [0,1) of
// f(x) = (r, g, b)(x), RIS over M uniform candidates with the luminance target. Both estimators
// must have the integral as their mean (z < 5 over 2^16 fixed-seed trials: a false failure has
// probability < 1e-6 per channel), and the candidate sum must have the lower variance in every
// channel (it is the conditional expectation of f(Y) W_Y given the candidates). Accumulating w f
// without the 1 / p-hat, or only the selected candidate, fails (checked when written).
#include <gtest/gtest.h>

#include <cmath>

#include "restir/gris.h"
#include "sampling/rng.h"

namespace strata::gpu {
namespace {

vec3 colour(double x) {  // a red lobe, a green ramp, a blue step: the chroma varies along x
  return vec3(float(std::exp(-20.0 * (x - 0.3) * (x - 0.3))), float(0.2 + 0.6 * x), float(x > 0.7 ? 0.9 : 0.05));
}
float lum(vec3 c) { return 0.2126f * c.r + 0.7152f * c.g + 0.0722f * c.b; }

struct Moments {
  double sum[3] = {0, 0, 0}, sum2[3] = {0, 0, 0};
  void add(vec3 v) {
    for (int c = 0; c < 3; ++c) {
      sum[c] += v[c];
      sum2[c] += double(v[c]) * v[c];
    }
  }
  double mean(int c, int n) const { return sum[c] / n; }
  double variance(int c, int n) const { return sum2[c] / n - mean(c, n) * mean(c, n); }
};

TEST(RestirEstimate, CandidateSumIsUnbiasedWithLessVarianceThanTheSelectedSample) {
  double exact[3] = {0, 0, 0};
  const int grid = 1 << 18;
  for (int i = 0; i < grid; ++i) {
    vec3 f = colour((i + 0.5) / grid);
    for (int c = 0; c < 3; ++c) exact[c] += double(f[c]) / grid;
  }
  const int trials = 1 << 16, m = 4;
  Moments selected, summed;
  for (int t = 0; t < trials; ++t) {
    Rng rng = rng_init(uint(t), 0x3E57u, 0, 7);
    GrisState s = gris_begin();
    vec3 f_selected(0.0f);
    for (int i = 0; i < m; ++i) {
      vec3 f = colour(rng_next_float(rng));
      float p_hat = lum(f);
      if (gris_stream_path(s, p_hat / float(m), p_hat, f, 1.0f, uint(i), rng_next_float(rng))) f_selected = f;
    }
    selected.add(f_selected * gris_ucw(s));  // RS-main Eq. 5
    summed.add(s.estimate);
  }
  for (int c = 0; c < 3; ++c) {
    double se_sel = std::sqrt(selected.variance(c, trials) / trials);
    double se_sum = std::sqrt(summed.variance(c, trials) / trials);
    EXPECT_LT(std::abs(selected.mean(c, trials) - exact[c]), 5.0 * se_sel) << "channel " << c;
    EXPECT_LT(std::abs(summed.mean(c, trials) - exact[c]), 5.0 * se_sum) << "channel " << c;
    EXPECT_LT(summed.variance(c, trials), selected.variance(c, trials)) << "channel " << c;
    std::printf("channel %d: exact %.5f, f(Y)W %.5f (var %.5f), candidate sum %.5f (var %.5f)\n", c, exact[c],
                selected.mean(c, trials), selected.variance(c, trials), summed.mean(c, trials), summed.variance(c, trials));
  }
}

// A candidate with a weight that is not a finite non-negative number adds nothing to the estimate.
TEST(RestirEstimate, NonFiniteWeightsAreLeftOut) {
  GrisState s = gris_begin();
  gris_stream_path(s, std::nanf(""), 1.0f, vec3(1.0f), 1.0f, 0u, 0.5f);
  gris_stream_path(s, INFINITY, 1.0f, vec3(1.0f), 1.0f, 1u, 0.5f);
  gris_stream_path(s, 1.0f, 0.0f, vec3(1.0f), 1.0f, 2u, 0.5f);
  gris_stream_path(s, 2.0f, 4.0f, vec3(8.0f, 4.0f, 0.0f), 1.0f, 3u, 0.5f);
  EXPECT_EQ(s.estimate, vec3(4.0f, 2.0f, 0.0f));
}

}  // namespace
}  // namespace strata::gpu
