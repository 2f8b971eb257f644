// GRIS is unbiased with the library's weights: a 1D model of ReSTIR where the exact answer is
// known. Pixel j integrates f_j over [0,1). Its canonical sample is one uniform draw; "previous
// frame" neighbours resample their own integrands f_i by RIS and are shifted into pixel j by the
// bijection T(x) = x^2 (Jacobian 2x, inverse sqrt(y)), so Jacobians and p-hat-from values
// (RS-main Eq. 4-7) all matter. E[f_j(Y) W_Y] must equal the integral of f_j exactly, for both
// the generalized balance heuristic and pairwise MIS. Dropping the Jacobian or using an MIS
// weight that does not sum to one makes these tests fail (checked when they were written).
#include <gtest/gtest.h>

#include <cmath>
#include <functional>

#include "restir/gris.h"
#include "sampling/rng.h"

namespace strata::gpu {
namespace {

using Fn = std::function<double(double)>;

double integral(const Fn& f) {  // midpoint rule, error ~1e-12 for these smooth functions
  const int n = 1 << 20;
  double s = 0.0;
  for (int i = 0; i < n; ++i) s += f((i + 0.5) / n);
  return s / n;
}

double shift(double x) { return x * x; }                    // T: previous domain -> pixel j
double shift_jacobian(double x) { return 2.0 * x; }         // |dT/dx|
double inverse_shift(double y) { return std::sqrt(y); }     // T^-1
double inverse_jacobian(double y) { return y > 0.0 ? 0.5 / std::sqrt(y) : 0.0; }

struct Candidate {
  double x = 0.0;    // in its own domain
  double ucw = 0.0;  // W_X
  double confidence = 0.0;
};

// RIS in a domain with target p_hat from m uniform candidates: W = (1/p_hat(X)) (1/m) sum p_hat(x_i).
Candidate ris(const Fn& p_hat, int m, Rng& rng) {
  GrisState s = gris_begin();
  double xs[64];
  for (int i = 0; i < m; ++i) {
    xs[i] = rng_next_float(rng);
    float w = float(p_hat(xs[i]) / m);
    gris_stream(s, w, float(p_hat(xs[i])), 1.0f, uint(i), rng_next_float(rng));
  }
  return {xs[s.selected], double(gris_ucw(s)), double(m)};
}

struct Estimate {
  double mean = 0.0, se = 0.0;
};

// One pixel's estimator over `trials` independent runs. `pairwise` selects the MIS.
Estimate run(const Fn& f_j, const std::vector<Fn>& f_neighbors, bool pairwise, int trials, uint seed) {
  double sum = 0.0, sum2 = 0.0;
  const float k = float(f_neighbors.size());
  for (int t = 0; t < trials; ++t) {
    Rng rng = rng_init(uint(t), 0, 0, seed);
    // Canonical: one uniform sample in pixel j (W = 1 / pdf = 1, confidence 1).
    Candidate canonical{rng_next_float(rng), 1.0, 1.0};
    std::vector<Candidate> prev;
    for (const auto& f_i : f_neighbors) prev.push_back(ris(f_i, 4, rng));
    double c_total = canonical.confidence;
    for (const auto& c : prev) c_total += c.confidence;

    // p-hat-from of neighbour i at a path y of pixel j (RS-main Eq. 7).
    auto p_from = [&](size_t i, double y) { return f_neighbors[i](inverse_shift(y)) * inverse_jacobian(y); };

    GrisState s = gris_begin();
    double ys[16];
    // Canonical sample's weight (RS-main Eq. 4 with identity shift).
    double y_c = canonical.x;
    double m_c = 0.0;
    if (pairwise) {
      for (size_t i = 0; i < prev.size(); ++i)
        m_c += mis_pairwise_canonical_term(float(prev[i].confidence), float(p_from(i, y_c)), float(canonical.confidence),
                                           float(f_j(y_c)), k, float(c_total));
    } else if (prev.size() == 1) {  // the library's two-domain form (RS-main Eq. 13)
      m_c = mis_balance2(float(canonical.confidence), float(f_j(y_c)), float(prev[0].confidence), float(p_from(0, y_c)));
    } else {  // RS-main Eq. 6 over all domains
      double denom = canonical.confidence * f_j(y_c);
      for (size_t i = 0; i < prev.size(); ++i) denom += prev[i].confidence * p_from(i, y_c);
      m_c = canonical.confidence * f_j(y_c) / denom;
    }
    ys[0] = y_c;
    gris_stream(s, gris_resampling_weight(float(m_c), float(f_j(y_c)), float(canonical.ucw), 1.0f), float(f_j(y_c)), 1.0f,
                0, rng_next_float(rng));
    // Shifted neighbours.
    for (size_t i = 0; i < prev.size(); ++i) {
      double y = shift(prev[i].x);
      double m_i;
      if (pairwise) {
        m_i = mis_pairwise_neighbor(float(prev[i].confidence), float(p_from(i, y)), float(canonical.confidence), float(f_j(y)), k,
                                    float(c_total));
      } else if (prev.size() == 1) {  // RS-main Eq. 11
        m_i = mis_balance2(float(prev[0].confidence), float(p_from(0, y)), float(canonical.confidence), float(f_j(y)));
      } else {
        double denom = canonical.confidence * f_j(y);
        for (size_t l = 0; l < prev.size(); ++l) denom += prev[l].confidence * p_from(l, y);
        m_i = prev[i].confidence * p_from(i, y) / denom;
      }
      ys[i + 1] = y;
      float w = gris_resampling_weight(float(m_i), float(f_j(y)), float(prev[i].ucw), float(shift_jacobian(prev[i].x)));
      gris_stream(s, w, float(f_j(y)), float(prev[i].confidence), uint(i + 1), rng_next_float(rng));
    }
    double estimate = s.selected == GRIS_NONE ? 0.0 : f_j(ys[s.selected]) * double(gris_ucw(s));
    sum += estimate;
    sum2 += estimate * estimate;
  }
  double mean = sum / trials;
  return {mean, std::sqrt(std::max(0.0, sum2 / trials - mean * mean) / trials)};
}

const Fn f_pixel = [](double x) { return 1.0 + 0.8 * std::sin(6.0 * x) + 2.0 * x * x; };
const Fn f_prev_a = [](double x) { return 0.5 + x; };
const Fn f_prev_b = [](double x) { return 1.5 - std::cos(3.0 * x); };

// 5 standard errors: a false failure has probability 6e-7; a dropped Jacobian shifts the mean by
// tens of standard errors at 2e5 trials.
constexpr double kSigmas = 5.0;

TEST(RestirGrisUnbiased, BalanceHeuristicWithOneShiftedNeighbour) {
  Estimate e = run(f_pixel, {f_prev_a}, false, 200000, 1);
  EXPECT_NEAR(e.mean, integral(f_pixel), kSigmas * e.se) << "se " << e.se;
}

TEST(RestirGrisUnbiased, BalanceHeuristicWithTwoShiftedNeighbours) {
  Estimate e = run(f_pixel, {f_prev_a, f_prev_b}, false, 200000, 2);
  EXPECT_NEAR(e.mean, integral(f_pixel), kSigmas * e.se) << "se " << e.se;
}

TEST(RestirGrisUnbiased, PairwiseMisWithTwoShiftedNeighbours) {
  Estimate e = run(f_pixel, {f_prev_a, f_prev_b}, true, 200000, 3);
  EXPECT_NEAR(e.mean, integral(f_pixel), kSigmas * e.se) << "se " << e.se;
}

}  // namespace
}  // namespace strata::gpu
