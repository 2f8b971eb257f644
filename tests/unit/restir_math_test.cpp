// CPU tests of the resampling library's math (shaders/restir/*.h compiled as C++) against values
// computed by hand.
#include <gtest/gtest.h>

#include <cmath>
#include <vector>

#include "restir/gris.h"
#include "restir/reconnection.h"
#include "restir/reprojection.h"
#include "sampling/rng.h"

namespace strata::gpu {
namespace {

TEST(RestirGris, StreamingSelectionAndUcw) {
  GrisState s = gris_begin();
  // Weights 1 and 3: with u = 0.5 the first is taken (0.5*1 < 1), then the second replaces it when
  // u * 4 < 3.
  EXPECT_TRUE(gris_stream(s, 1.0f, 2.0f, 1.0f, 0, 0.5f));
  EXPECT_TRUE(gris_stream(s, 3.0f, 6.0f, 5.0f, 1, 0.5f));
  EXPECT_EQ(s.selected, 1u);
  EXPECT_FLOAT_EQ(s.weight_sum, 4.0f);
  EXPECT_FLOAT_EQ(s.confidence, 6.0f);
  EXPECT_FLOAT_EQ(gris_ucw(s), 4.0f / 6.0f);  // RS-main Eq. 5
  EXPECT_FALSE(gris_stream(s, 1.0f, 1.0f, 1.0f, 2, 0.9f));  // 0.9 * 5 >= 1
  EXPECT_EQ(s.selected, 1u);
}

TEST(RestirGris, NonFiniteWeightsAreRejectedAndCounted) {
  GrisState s = gris_begin();
  float inf = std::numeric_limits<float>::infinity();
  float nan = std::numeric_limits<float>::quiet_NaN();
  EXPECT_FALSE(gris_stream(s, nan, 1.0f, 1.0f, 0, 0.0f));
  EXPECT_FALSE(gris_stream(s, inf, 1.0f, 1.0f, 1, 0.0f));
  EXPECT_FALSE(gris_stream(s, -1.0f, 1.0f, 1.0f, 2, 0.0f));
  EXPECT_FALSE(gris_stream(s, 1.0f, nan, 1.0f, 3, 0.0f));
  EXPECT_EQ(s.rejected, 4u);
  EXPECT_EQ(s.selected, GRIS_NONE);
  EXPECT_EQ(gris_ucw(s), 0.0f);
  EXPECT_FLOAT_EQ(s.confidence, 4.0f);  // confidence still counts: the domains were there
  EXPECT_EQ(gris_sanitize(nan), 0.0f);
  EXPECT_EQ(gris_sanitize(inf), 0.0f);
  EXPECT_EQ(gris_sanitize(2.0f), 2.0f);
}

// The selection probability of candidate i is w_i / sum w (the basis of the UCW).
TEST(RestirGris, SelectionFrequenciesFollowTheWeights) {
  const float w[4] = {0.5f, 2.0f, 0.0f, 1.5f};
  int counts[4] = {0, 0, 0, 0};
  Rng rng = rng_init(1, 1, 1, 1);
  const int n = 200000;
  for (int t = 0; t < n; ++t) {
    GrisState s = gris_begin();
    for (uint i = 0; i < 4; ++i) gris_stream(s, w[i], 1.0f, 1.0f, i, rng_next_float(rng));
    counts[s.selected]++;
  }
  for (int i = 0; i < 4; ++i) {
    double p = w[i] / 4.0;
    double se = std::sqrt(p * (1 - p) / n);
    EXPECT_NEAR(double(counts[i]) / n, p, 5 * se + 1e-9) << i;
  }
}

TEST(RestirGris, ConfidenceCapAndPHatFrom) {
  EXPECT_FLOAT_EQ(confidence_capped(7.0f, 20.0f), 7.0f);
  EXPECT_FLOAT_EQ(confidence_capped(27.0f, 20.0f), 20.0f);
  EXPECT_FLOAT_EQ(confidence_capped(27.0f, 4.0f), 4.0f);
  EXPECT_FLOAT_EQ(p_hat_from(3.0f, 0.5f), 1.5f);  // RS-main Eq. 7
  EXPECT_EQ(p_hat_from(3.0f, std::numeric_limits<float>::infinity()), 0.0f);
}

TEST(RestirMis, BalanceHeuristicOfTwoDomains) {
  // RS-main Eq. 11 with c_i = 4, p_prev |J|^-1 = 0.5, c* = 1, p-hat(Y) = 2: 4*0.5 / (1*2 + 4*0.5).
  EXPECT_FLOAT_EQ(mis_balance2(4.0f, 0.5f, 1.0f, 2.0f), 0.5f);
  // And Eq. 13 for the canonical side at the same values: complementary.
  EXPECT_FLOAT_EQ(mis_balance2(1.0f, 2.0f, 4.0f, 0.5f), 0.5f);
  EXPECT_FLOAT_EQ(mis_balance2(1.0f, 3.0f, 2.0f, 0.0f), 1.0f);  // failed reverse shift: canonical keeps all
  EXPECT_FLOAT_EQ(mis_balance2(1.0f, 0.0f, 2.0f, 0.0f), 0.0f);
}

TEST(RestirMis, PairwiseWeightsSumToOneForEveryPath) {
  // Canonical confidence 1, neighbours with confidence 3 and 6 (k = 2, C = 10). For an arbitrary
  // path, the p-hat-from values of each domain are given; the weights of all strategies sum to 1.
  const float cc = 1.0f, c[2] = {3.0f, 6.0f}, k = 2.0f, total = 10.0f;
  const float p_c = 0.8f, p_from[2] = {0.3f, 1.7f};
  float canonical = 0.0f;
  for (int i = 0; i < 2; ++i) canonical += mis_pairwise_canonical_term(c[i], p_from[i], cc, p_c, k, total);
  float neighbors = 0.0f;
  for (int i = 0; i < 2; ++i) neighbors += mis_pairwise_neighbor(c[i], p_from[i], cc, p_c, k, total);
  EXPECT_NEAR(canonical + neighbors, 1.0f, 1e-6f);
  // Hand value for neighbour 0: share (3 + 0.5)/10 = 0.35; pair weight 3*0.3 / (3*0.3 + 0.5*0.8) = 0.9/1.3.
  EXPECT_NEAR(mis_pairwise_neighbor(3.0f, 0.3f, cc, p_c, k, total), 0.35f * 0.9f / 1.3f, 1e-6f);
  // When every domain has the same p-hat, pairwise equals the confidence-weighted balance heuristic.
  float same = 0.6f;
  EXPECT_NEAR(mis_pairwise_neighbor(3.0f, same, cc, same, k, total), 3.0f / 10.0f, 1e-6f);
  float canonical_same = 0.0f;
  for (int i = 0; i < 2; ++i) canonical_same += mis_pairwise_canonical_term(c[i], same, cc, same, k, total);
  EXPECT_NEAR(canonical_same, 1.0f / 10.0f, 1e-6f);
}

TEST(RestirReconnection, JacobianHandValues) {
  // x_k at the origin with normal +z. Base previous vertex straight above at distance 2 (cos 1);
  // offset previous vertex at (3, 0, 3): distance^2 18, cos 1/sqrt(2).
  vec3 xk(0.0f), n(0.0f, 0.0f, 1.0f);
  float j = reconnection_jacobian(xk, n, vec3(0, 0, 2), vec3(3, 0, 3));
  EXPECT_NEAR(j, (1.0f / std::sqrt(2.0f)) / 1.0f * (4.0f / 18.0f), 1e-6f);
  // Identity when the offset vertex is the base vertex.
  EXPECT_NEAR(reconnection_jacobian(xk, n, vec3(1, 2, 3), vec3(1, 2, 3)), 1.0f, 1e-6f);
  // The inverse shift's Jacobian is the reciprocal.
  float back = reconnection_jacobian(xk, n, vec3(3, 0, 3), vec3(0, 0, 2));
  EXPECT_NEAR(j * back, 1.0f, 1e-5f);
}

TEST(RestirReconnection, SingularCasesFailTheShift) {
  vec3 xk(0.0f), n(0.0f, 0.0f, 1.0f);
  EXPECT_EQ(reconnection_jacobian(xk, n, vec3(0, 0, 1), vec3(1, 0, 0)), 0.0f);       // grazing offset edge
  EXPECT_EQ(reconnection_jacobian(xk, n, vec3(1, 0, 1e-6f), vec3(0, 0, 1)), 0.0f);  // grazing base edge
  EXPECT_EQ(reconnection_jacobian(xk, n, vec3(0.0f), vec3(0, 0, 1)), 0.0f);         // coincident vertices
  EXPECT_EQ(reconnection_jacobian(xk, n, vec3(0, 0, 1000), vec3(0, 0, 0.001f)), 0.0f);  // J = 1e12: refused
  // The rules the shaders apply (restir/path_vertex.glsl calls these): roughness, no specular lobe,
  // relative edge length, grazing angle at the reconnection vertex.
  EXPECT_TRUE(rough_vertex(0.3f, 0.04f));
  EXPECT_TRUE(rough_vertex(0.04f, 0.04f));   // glossy (carousel's red glossy): at or above RECONNECT_MIN_ALPHA
  EXPECT_FALSE(rough_vertex(0.02f, 0.04f));  // near-specular
  EXPECT_FALSE(rough_vertex(4e-4f, 0.9f));   // the stiff scene's mirror
  EXPECT_TRUE(rough_vertex(0.0f, 0.0f));    // smooth but without a specular lobe: purely diffuse
  EXPECT_TRUE(reconnectable(true, true, 1.0f, 10.0f, 0.5f));
  EXPECT_FALSE(reconnectable(false, true, 1.0f, 10.0f, 0.5f));   // near-specular previous vertex
  EXPECT_FALSE(reconnectable(true, false, 1.0f, 10.0f, 0.5f));   // near-specular reconnection vertex
  EXPECT_FALSE(reconnectable(true, true, 0.05f, 10.0f, 0.5f));   // edge shorter than 1% of the camera distance
  EXPECT_FALSE(reconnectable(true, true, 1.0f, 10.0f, 1e-4f));   // grazing reconnection vertex
  EXPECT_TRUE(reconnectable_end(true, true, 0.0f, 10.0f, 0.0f));  // an escaped end needs only a rough x_{n-1}
  EXPECT_FALSE(reconnectable_end(false, true, 0.0f, 10.0f, 1.0f));
  EXPECT_FALSE(reconnectable_end(true, false, 0.05f, 10.0f, 1.0f));
}

TEST(RestirReprojection, JacobianHandValues) {
  vec3 fwd(0.0f, 0.0f, -1.0f);
  // A hit straight ahead, facing the camera, at distance 2 before and 4 after (camera moved back):
  // the hit covers a quarter of the subpixel area it did, so |du/dv| = 4 / 16.
  PrimaryView prev = primary_view(vec3(0, 0, -2), vec3(0, 0, 1), vec3(0.0f), fwd);
  PrimaryView cur = primary_view(vec3(0, 0, -2), vec3(0, 0, 1), vec3(0, 0, 2), fwd);
  EXPECT_NEAR(reprojection_jacobian(prev, cur, 1.0f), 0.25f, 1e-6f);
  EXPECT_NEAR(reprojection_jacobian(cur, prev, 1.0f), 4.0f, 1e-5f);
  // Off-axis by 45 degrees, normal still facing the camera: cos_N = 1, cos_V = 1/sqrt(2):
  // relative to on-axis at the same distance the factor is cos^3 (prev) / cos^3 (cur).
  PrimaryView off = primary_view(vec3(2, 0, -2), normalize(vec3(-1, 0, 1)), vec3(0.0f), fwd);
  PrimaryView on = primary_view(vec3(0, 0, -std::sqrt(8.0f)), vec3(0, 0, 1), vec3(0.0f), fwd);
  float c3 = std::pow(1.0f / std::sqrt(2.0f), 3.0f);
  EXPECT_NEAR(reprojection_jacobian(on, off, 1.0f), 1.0f / c3, 1e-4f);
  // Non-rigid scale multiplies by the area ratio.
  EXPECT_NEAR(reprojection_jacobian(prev, prev, 2.0f), 2.0f, 1e-6f);
  // Grazing or behind the camera: the shift fails.
  PrimaryView grazing = primary_view(vec3(0, 0, -2), vec3(1, 0, 0), vec3(0.0f), fwd);
  EXPECT_EQ(reprojection_jacobian(prev, grazing, 1.0f), 0.0f);
  PrimaryView behind = primary_view(vec3(0, 0, 2), vec3(0, 0, -1), vec3(0.0f), fwd);
  EXPECT_EQ(reprojection_jacobian(prev, behind, 1.0f), 0.0f);
}

}  // namespace
}  // namespace strata::gpu
