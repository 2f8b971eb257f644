#pragma once
// Colour spaces and the colour metric of FLIP (Andersson et al. 2020, "FLIP: A Difference Evaluator
// for Alternating Images", HPG 2020; cited below as FLIP20 with the title of the section, "colour
// pipeline" or "feature pipeline"). Internal to strata_metrics; exposed in a header so that the unit
// tests can check the round trips and the constants.
//
// Spaces: sRGB (display, OETF-encoded) <-> linear RGB (Rec. 709 primaries, D65) <-> CIE XYZ <->
// YCxCz (the linearized opponent space of the spatial filtering step) and XYZ -> CIELAB.
#include <algorithm>
#include <array>
#include <cmath>

namespace strata::metrics::detail {

using Color3 = std::array<double, 3>;

// ---- constants of the paper -------------------------------------------------------------------
inline constexpr double kQc = 0.7;   // colour-difference exponent q_c (FLIP20 colour pipeline)
inline constexpr double kPc = 0.4;   // p_c: the knee of the error redistribution, as a share of c_max
inline constexpr double kPt = 0.95;  // p_t: the error assigned at the knee p_c * c_max
inline constexpr double kQf = 0.5;   // feature-difference exponent q_f (FLIP20 feature pipeline)
// w: peak-to-trough width, in degrees, of the edge detector (FLIP20 feature pipeline).
inline constexpr double kFeatureWidthDeg = 0.082;

// ---- sRGB transfer function (IEC 61966-2-1) ----------------------------------------------------
inline double srgb_to_linear(double c) {
  return c <= 0.04045 ? c / 12.92 : std::pow((c + 0.055) / 1.055, 2.4);
}
inline double linear_to_srgb(double c) {
  return c <= 0.0031308 ? 12.92 * c : 1.055 * std::pow(c, 1.0 / 2.4) - 0.055;
}

// ---- linear RGB <-> XYZ -----------------------------------------------------------------------
// The matrix is derived at compile time from the sRGB primaries and the D65 white chromaticity
// (R 0.64,0.33  G 0.30,0.60  B 0.15,0.06  W 0.3127,0.3290), so that RGB (1,1,1) is exactly the
// white point used by YCxCz and CIELAB below.
namespace colour_math {
using M3 = std::array<std::array<double, 3>, 3>;
constexpr M3 inverse(const M3& m) {
  const double det = m[0][0] * (m[1][1] * m[2][2] - m[1][2] * m[2][1]) -
                     m[0][1] * (m[1][0] * m[2][2] - m[1][2] * m[2][0]) +
                     m[0][2] * (m[1][0] * m[2][1] - m[1][1] * m[2][0]);
  M3 r{};
  r[0][0] = (m[1][1] * m[2][2] - m[1][2] * m[2][1]) / det;
  r[0][1] = (m[0][2] * m[2][1] - m[0][1] * m[2][2]) / det;
  r[0][2] = (m[0][1] * m[1][2] - m[0][2] * m[1][1]) / det;
  r[1][0] = (m[1][2] * m[2][0] - m[1][0] * m[2][2]) / det;
  r[1][1] = (m[0][0] * m[2][2] - m[0][2] * m[2][0]) / det;
  r[1][2] = (m[0][2] * m[1][0] - m[0][0] * m[1][2]) / det;
  r[2][0] = (m[1][0] * m[2][1] - m[1][1] * m[2][0]) / det;
  r[2][1] = (m[0][1] * m[2][0] - m[0][0] * m[2][1]) / det;
  r[2][2] = (m[0][0] * m[1][1] - m[0][1] * m[1][0]) / det;
  return r;
}
constexpr M3 rgb_to_xyz_matrix() {
  const double xy[3][2] = {{0.64, 0.33}, {0.30, 0.60}, {0.15, 0.06}};
  const double wx = 0.3127, wy = 0.3290;
  M3 p{};  // columns: XYZ of each primary with Y = 1
  for (int c = 0; c < 3; ++c) {
    p[0][c] = xy[c][0] / xy[c][1];
    p[1][c] = 1.0;
    p[2][c] = (1.0 - xy[c][0] - xy[c][1]) / xy[c][1];
  }
  const std::array<double, 3> white = {wx / wy, 1.0, (1.0 - wx - wy) / wy};
  const M3 pi = inverse(p);
  M3 m{};
  for (int c = 0; c < 3; ++c) {
    const double s = pi[c][0] * white[0] + pi[c][1] * white[1] + pi[c][2] * white[2];
    for (int r = 0; r < 3; ++r) m[r][c] = p[r][c] * s;
  }
  return m;
}
}  // namespace colour_math

inline constexpr colour_math::M3 kRgbToXyz = colour_math::rgb_to_xyz_matrix();
inline constexpr colour_math::M3 kXyzToRgb = colour_math::inverse(kRgbToXyz);
// The reference white (D65, Y = 1): XYZ of linear RGB (1,1,1).
inline constexpr Color3 kWhite = {kRgbToXyz[0][0] + kRgbToXyz[0][1] + kRgbToXyz[0][2],
                                  kRgbToXyz[1][0] + kRgbToXyz[1][1] + kRgbToXyz[1][2],
                                  kRgbToXyz[2][0] + kRgbToXyz[2][1] + kRgbToXyz[2][2]};

inline Color3 mul(const colour_math::M3& m, const Color3& v) {
  return {m[0][0] * v[0] + m[0][1] * v[1] + m[0][2] * v[2], m[1][0] * v[0] + m[1][1] * v[1] + m[1][2] * v[2],
          m[2][0] * v[0] + m[2][1] * v[1] + m[2][2] * v[2]};
}
inline Color3 linear_rgb_to_xyz(const Color3& rgb) { return mul(kRgbToXyz, rgb); }
inline Color3 xyz_to_linear_rgb(const Color3& xyz) { return mul(kXyzToRgb, xyz); }

// ---- YCxCz (FLIP20 colour pipeline, spatial filtering: the space the CSFs are applied in) ------
// Y' = 116 Y/Yn - 16, Cx = 500 (X/Xn - Y/Yn), Cz = 200 (Y/Yn - Z/Zn): CIELAB without the cube root.
inline Color3 xyz_to_ycxcz(const Color3& xyz) {
  const double x = xyz[0] / kWhite[0], y = xyz[1] / kWhite[1], z = xyz[2] / kWhite[2];
  return {116.0 * y - 16.0, 500.0 * (x - y), 200.0 * (y - z)};
}
inline Color3 ycxcz_to_xyz(const Color3& ycc) {
  const double y = (ycc[0] + 16.0) / 116.0;
  return {kWhite[0] * (y + ycc[1] / 500.0), kWhite[1] * y, kWhite[2] * (y - ycc[2] / 200.0)};
}
inline Color3 linear_rgb_to_ycxcz(const Color3& rgb) { return xyz_to_ycxcz(linear_rgb_to_xyz(rgb)); }
inline Color3 ycxcz_to_linear_rgb(const Color3& ycc) { return xyz_to_linear_rgb(ycxcz_to_xyz(ycc)); }
inline Color3 srgb_to_ycxcz(const Color3& srgb) {
  return linear_rgb_to_ycxcz({srgb_to_linear(srgb[0]), srgb_to_linear(srgb[1]), srgb_to_linear(srgb[2])});
}
inline Color3 ycxcz_to_srgb(const Color3& ycc) {
  const Color3 rgb = ycxcz_to_linear_rgb(ycc);
  return {linear_to_srgb(rgb[0]), linear_to_srgb(rgb[1]), linear_to_srgb(rgb[2])};
}

// ---- CIELAB, Hunt adjustment, HyAB (FLIP20 colour pipeline, colour metric) ----------------------
inline double lab_f(double t) {
  constexpr double d = 6.0 / 29.0;
  return t > d * d * d ? std::cbrt(t) : t / (3.0 * d * d) + 4.0 / 29.0;
}
inline Color3 xyz_to_lab(const Color3& xyz) {
  const double fx = lab_f(xyz[0] / kWhite[0]), fy = lab_f(xyz[1] / kWhite[1]), fz = lab_f(xyz[2] / kWhite[2]);
  return {116.0 * fy - 16.0, 500.0 * (fx - fy), 200.0 * (fy - fz)};
}
// Hunt effect: chroma shrinks with lightness, a' = 0.01 L a, b' = 0.01 L b.
inline Color3 hunt_adjust(const Color3& lab) { return {lab[0], 0.01 * lab[0] * lab[1], 0.01 * lab[0] * lab[2]}; }
inline Color3 linear_rgb_to_hunt_lab(const Color3& rgb) { return hunt_adjust(xyz_to_lab(linear_rgb_to_xyz(rgb))); }
// HyAB distance: |dL| + ||(da, db)||.
inline double hyab(const Color3& a, const Color3& b) {
  return std::abs(a[0] - b[0]) + std::hypot(a[1] - b[1], a[2] - b[2]);
}

// c_max = HyAB(Hunt(Lab(green)), Hunt(Lab(blue)))^q_c: the largest distance between two colours of
// the linear RGB cube after the Hunt adjustment (FLIP20 colour pipeline, colour metric).
inline double max_colour_distance() {
  static const double cmax =
      std::pow(hyab(linear_rgb_to_hunt_lab({0.0, 1.0, 0.0}), linear_rgb_to_hunt_lab({0.0, 0.0, 1.0})), kQc);
  return cmax;
}

// FLIP20 colour pipeline, error redistribution: e = HyAB^q_c, then [0, p_c c_max) maps linearly to
// [0, p_t) and [p_c c_max, c_max] to [p_t, 1]; the result is clamped to [0, 1].
inline double remap_colour_error(double hyab_distance) {
  const double cmax = max_colour_distance();
  const double knee = kPc * cmax;
  const double e = std::pow(hyab_distance, kQc);
  const double out = e < knee ? e * (kPt / knee) : kPt + (e - knee) / (cmax - knee) * (1.0 - kPt);
  return std::min(out, 1.0);
}

}  // namespace strata::metrics::detail
