#pragma once
// FLIP internals shared by flip.cpp and hdr_flip.cpp and the unit tests: float planes, the CSF and
// feature filters (FLIP20 colour pipeline / feature pipeline) and separable filtering.
#include <cstdint>
#include <functional>
#include <vector>

#include "image/image.h"

namespace strata::metrics::detail {

// One channel of an image, row-major, top row first.
struct Plane {
  uint32_t width = 0, height = 0;
  std::vector<float> v;
  Plane() = default;
  Plane(uint32_t w, uint32_t h) : width(w), height(h), v(size_t(w) * h, 0.0f) {}
  float& at(uint32_t x, uint32_t y) { return v[size_t(y) * width + x]; }
  float at(uint32_t x, uint32_t y) const { return v[size_t(y) * width + x]; }
};

// ---- contrast sensitivity functions (FLIP20 colour pipeline, spatial filtering) ---------------
// Each CSF is, in the spatial domain, a sum of two Gaussians of the visual angle r (degrees):
//   s(r) = a1 sqrt(pi/b1) exp(-pi^2 r^2 / b1) + a2 sqrt(pi/b2) exp(-pi^2 r^2 / b2)
// sampled at r = |(dx, dy)| / pixels_per_degree on a (2R+1)^2 grid and normalized to sum to 1.
struct CsfConstants {
  double a1, b1, a2, b2;
};
inline constexpr CsfConstants kCsfAchromatic = {1.0, 0.0047, 0.0, 1e-5};  // Y
inline constexpr CsfConstants kCsfRedGreen = {1.0, 0.0053, 0.0, 1e-5};    // Cx
inline constexpr CsfConstants kCsfBlueYellow = {34.1, 0.04, 13.5, 0.025}; // Cz

// R = ceil(3 * sqrt(b_max / (2 pi^2)) * ppd), b_max the largest b of the three CSFs: three standard
// deviations of the widest Gaussian. One radius serves all three channels.
int csf_radius(double pixels_per_degree);

// A 2D CSF kernel as a sum of (at most two) separable Gaussians:
//   K(dx, dy) = w[0] g0(dx) g0(dy) + w[1] g1(dx) g1(dy)
// with each 1D g summing to 1 and w[0] + w[1] = 1, which is exactly the sampled s(r) above divided
// by its sum over the square grid (each Gaussian in r^2 = dx^2 + dy^2 factors into x and y).
struct CsfKernel {
  int radius = 0;
  std::vector<float> g[2];
  double w[2] = {1.0, 0.0};
};
CsfKernel csf_kernel(const CsfConstants& c, double pixels_per_degree);

// ---- feature detectors (FLIP20 feature pipeline) ------------------------------------------------
// Gaussian of standard deviation sigma = 0.5 * w * ppd pixels (w = 0.082 degrees), radius
// ceil(3 sigma), and its first and second derivatives along x. The 2D edge filter in x is
// d1(dx) g(dy), the point filter d2(dx) g(dy) (transposed for y). g sums to 1; the positive and the
// negative weights of d1 and d2 sum to +1 and -1 respectively, which (as g sums to 1) is the same
// normalization of the 2D kernels.
struct FeatureKernels {
  int radius = 0;
  double sigma = 0.0;
  std::vector<float> g, d1, d2;
};
FeatureKernels feature_kernels(double pixels_per_degree);

// out(x, y) = sum_i kx[i] in(x + i - R, y) then the same with ky along y; pixels outside the image
// take the value of the nearest edge pixel (clamp-to-edge). kx and ky have 2R+1 taps.
Plane filter_separable(const Plane& in, const std::vector<float>& kx, const std::vector<float>& ky);
// The 2D CSF filter of a plane (one or two separable passes, weighted).
Plane filter_csf(const Plane& in, const CsfKernel& k);

// Runs body(y) for y in [0, rows) on the hardware threads (contiguous blocks of rows).
void parallel_rows(uint32_t rows, const std::function<void(uint32_t)>& body);

// ---- the LDR-FLIP core ---------------------------------------------------------------------------
// Linear RGB (each channel clamped to [0, 1] by the caller) as three planes.
struct LinearRgb {
  Plane r, g, b;
};
// Per-pixel LDR-FLIP error between two linear-RGB images of the same size.
std::vector<float> ldr_flip_linear(const LinearRgb& test, const LinearRgb& reference, double pixels_per_degree);
// Throws MetricError unless pixels_per_degree is finite and > 0.
void check_ppd(double pixels_per_degree);

// ---- HDR-FLIP (Andersson et al. 2021, "Visualizing Errors in Rendered HDR Images") --------------
// The ACES filmic curve (Narkowicz fit with the 0.6 pre-exposure folded into the coefficients), as
// HDR-FLIP uses it, clamped to [0, 1]; x >= 0.
double aces_tonemap(double x);
// The x >= 0 with aces_tonemap(x) = t, for t in (0, 1).
double aces_input_for(double t);
// The automatic exposure range of the reference (see metrics.h for the finite-range rules).
struct ExposureRange {
  double start = 0.0, stop = 0.0;
};
ExposureRange automatic_exposure_range(const image::Image& reference);

}  // namespace strata::metrics::detail
