// CPU tests of the LoD vertex mapping's math (shaders/restir/lod_mapping.h compiled as C++): the
// Jacobian of LOD Eq. 6 against analytic UV maps, its barycentric form, degenerate triangles, and
// the greedy matching of LOD Alg. 1.
#include <gtest/gtest.h>

#include <cmath>
#include <limits>

#include "restir/lod_mapping.h"

namespace strata::gpu {
namespace {

constexpr float kPi = 3.14159265358979f;

// A plane scaled by s maps UV to world as (s u, s v, 0): |u x v| = s^2 everywhere, so Eq. 6 between
// two tessellations of planes scaled by s1 and s2 is (s2 / s1)^2, whatever the triangles.
TEST(LodEq6, ScaledPlaneIsTheSquareOfTheScaleRatio) {
  auto triangle_of = [](float s, vec2 t0, vec2 t1, vec2 t2) {
    return area_per_uv_area(vec3(s * t0, 0.0f), vec3(s * t1, 0.0f), vec3(s * t2, 0.0f), t0, t1, t2);
  };
  const float from = triangle_of(2.0f, {0.0f, 0.0f}, {0.25f, 0.0f}, {0.0f, 0.25f});  // a fine triangle
  const float to = triangle_of(3.0f, {0.0f, 0.0f}, {1.0f, 0.0f}, {1.0f, 1.0f});       // a coarse one
  EXPECT_NEAR(from, 4.0f, 1e-5f);
  EXPECT_NEAR(to, 9.0f, 1e-5f);
  EXPECT_NEAR(lod_jacobian(from, to), 9.0f / 4.0f, 1e-5f);
  EXPECT_NEAR(lod_jacobian(to, from), 4.0f / 9.0f, 1e-6f);
}

// A cylinder of radius R and height H unwrapped as uv = (phi / 2 pi, h / H) and tessellated with N
// segments: each quad's triangles are flat chords of width 2 R sin(pi / N), so |u x v| =
// N 2 R sin(pi / N) H on every triangle, and Eq. 6 between levels with N1 and N2 segments is
// N2 sin(pi / N2) / (N1 sin(pi / N1)).
float cylinder_area_per_uv(uint segments, float radius, float height, uint segment) {
  const float phi0 = 2.0f * kPi * float(segment) / float(segments);
  const float phi1 = 2.0f * kPi * float(segment + 1) / float(segments);
  const vec3 p0(radius * std::cos(phi0), 0.0f, radius * std::sin(phi0));
  const vec3 p1(radius * std::cos(phi1), 0.0f, radius * std::sin(phi1));
  const vec3 p2(radius * std::cos(phi1), height, radius * std::sin(phi1));
  const vec2 t0(float(segment) / float(segments), 0.0f);
  const vec2 t1(float(segment + 1) / float(segments), 0.0f);
  const vec2 t2(float(segment + 1) / float(segments), 1.0f);
  return area_per_uv_area(p0, p1, p2, t0, t1, t2);
}

TEST(LodEq6, CylinderUnwrapMatchesTheChordFormula) {
  const float radius = 0.7f;
  const float height = 2.0f;
  for (uint fine : {64u, 32u}) {
    for (uint coarse : {16u, 8u, 6u}) {
      SCOPED_TRACE(std::to_string(fine) + " -> " + std::to_string(coarse) + " segments");
      const float expected = float(coarse) * std::sin(kPi / float(coarse)) / (float(fine) * std::sin(kPi / float(fine)));
      const float j = lod_jacobian(cylinder_area_per_uv(fine, radius, height, 3), cylinder_area_per_uv(coarse, radius, height, 1));
      EXPECT_NEAR(j, expected, 1e-4f * expected);
      EXPECT_LT(j, 1.0f);  // a coarser polygon has less area than the finer one around the same axis
    }
  }
}

// The resolver's barycentric form times the render-space area ratio is Eq. 6.
TEST(LodEq6, BarycentricFormTimesAreaRatioIsEq6) {
  const vec3 p0(0.0f), p1(2.0f, 0.0f, 0.0f), p2(0.0f, 1.0f, 0.5f);
  const vec2 t0(0.1f, 0.1f), t1(0.3f, 0.1f), t2(0.1f, 0.25f);
  const vec3 q0(1.0f, 1.0f, 0.0f), q1(4.0f, 1.0f, 0.0f), q2(1.0f, 3.0f, 1.0f);
  const vec2 s0(0.0f, 0.0f), s1(0.6f, 0.0f), s2(0.0f, 0.5f);
  const float area_from = 0.5f * length(cross(p1 - p0, p2 - p0));
  const float area_to = 0.5f * length(cross(q1 - q0, q2 - q0));
  const float bary = lod_bary_jacobian(uv_double_area(t0, t1, t2), uv_double_area(s0, s1, s2));
  const float eq6 = lod_jacobian(area_per_uv_area(p0, p1, p2, t0, t1, t2), area_per_uv_area(q0, q1, q2, s0, s1, s2));
  EXPECT_NEAR(area_to / area_from * bary, eq6, 1e-5f * eq6);
}

TEST(LodEq6, DegenerateUvTriangleFailsWithoutNanOrInf) {
  const vec3 p0(0.0f), p1(1.0f, 0.0f, 0.0f), p2(0.0f, 1.0f, 0.0f);
  const vec2 t(0.5f, 0.5f);
  EXPECT_EQ(area_per_uv_area(p0, p1, p2, t, t, t), 0.0f);                                  // all three UVs equal
  EXPECT_EQ(area_per_uv_area(p0, p1, p2, {0.0f, 0.0f}, {1.0f, 1.0f}, {2.0f, 2.0f}), 0.0f);  // collinear UVs
  EXPECT_EQ(lod_jacobian(0.0f, 3.0f), 0.0f);
  EXPECT_EQ(lod_jacobian(3.0f, 0.0f), 0.0f);
  EXPECT_EQ(lod_bary_jacobian(0.0f, 1.0f), 0.0f);
  EXPECT_EQ(lod_bary_jacobian(1.0f, 0.0f), 0.0f);
  const float nan = std::numeric_limits<float>::quiet_NaN();
  const float inf = std::numeric_limits<float>::infinity();
  EXPECT_EQ(lod_jacobian(nan, 1.0f), 0.0f);
  EXPECT_EQ(lod_jacobian(1.0f, inf), 0.0f);
  EXPECT_EQ(lod_bary_jacobian(inf, 1.0f), 0.0f);
  EXPECT_EQ(lod_bary_jacobian(1e30f, 1e-11f), 0.0f);  // overflows to inf
  EXPECT_EQ(area_per_uv_area(vec3(nan), p1, p2, {0.0f, 0.0f}, {1.0f, 0.0f}, {0.0f, 1.0f}), 0.0f);
}

// LOD Alg. 1: the closest pair first; the inverse direction pairs the same points (tau stays a
// bijection); the point left over when X_2,v runs out is unmatched.
TEST(LodAlg1, GreedyMatchingIsClosestFirstAndSymmetric) {
  // X_1,v: the two halves of a mirrored plane at x = -1 and x = +1; X_2,v: the same two points
  // after a LoD switch moved them slightly.
  vec3 from[LOD_MAX_CANDIDATES] = {vec3(-1.0f, 0.0f, 0.0f), vec3(1.0f, 0.0f, 0.0f)};
  vec3 to[LOD_MAX_CANDIDATES] = {vec3(1.05f, 0.0f, 0.0f), vec3(-0.9f, 0.0f, 0.0f)};
  EXPECT_EQ(lod_match(from, 2, to, 2, 0), 1);
  EXPECT_EQ(lod_match(from, 2, to, 2, 1), 0);
  EXPECT_EQ(lod_match(to, 2, from, 2, 1), 0);  // the inverse mapping
  EXPECT_EQ(lod_match(to, 2, from, 2, 0), 1);

  // Greedy, not nearest-neighbour: a is nearest to c, but (b, c) is the closest pair overall, so a
  // gets d (and with one point on the target side, a stays unmatched).
  vec3 xs[LOD_MAX_CANDIDATES] = {vec3(0.0f), vec3(1.9f, 0.0f, 0.0f)};  // a, b
  vec3 ys[LOD_MAX_CANDIDATES] = {vec3(2.0f, 0.0f, 0.0f), vec3(-3.0f, 0.0f, 0.0f)};  // c, d
  EXPECT_EQ(lod_match(xs, 2, ys, 2, 1), 0);
  EXPECT_EQ(lod_match(xs, 2, ys, 2, 0), 1);
  EXPECT_EQ(lod_match(xs, 2, ys, 1, 0), -1);
  EXPECT_EQ(lod_match(xs, 2, ys, 1, 1), 0);
  EXPECT_EQ(lod_match(xs, 2, ys, 0, 0), -1);

  // Six cube faces sharing one UV square, as overlap-uv's cube: every face matches itself.
  vec3 faces[LOD_MAX_CANDIDATES] = {vec3(0.5f, 0, 0), vec3(-0.5f, 0, 0), vec3(0, 0.5f, 0), vec3(0, -0.5f, 0), vec3(0, 0, 0.5f), vec3(0, 0, -0.5f)};
  vec3 coarse[LOD_MAX_CANDIDATES];
  for (uint i = 0; i < 6; ++i) coarse[5 - i] = faces[i] * 1.02f;
  for (uint i = 0; i < 6; ++i) EXPECT_EQ(lod_match(faces, 6, coarse, 6, i), int(5 - i)) << "face " << i;
}

TEST(LodAlg1, SamePointToleranceIsRelative) {
  EXPECT_TRUE(same_lod_point(vec3(40.0f, 1.0f, 0.0f), vec3(40.0002f, 1.0f, 0.0f)));
  EXPECT_FALSE(same_lod_point(vec3(40.0f, 1.0f, 0.0f), vec3(40.01f, 1.0f, 0.0f)));
  EXPECT_TRUE(same_lod_point(vec3(0.0f), vec3(5e-6f, 0.0f, 0.0f)));
  EXPECT_FALSE(same_lod_point(vec3(0.0f), vec3(1e-4f, 0.0f, 0.0f)));
}

}  // namespace
}  // namespace strata::gpu
