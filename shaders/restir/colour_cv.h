// How far the colour control variate moves a pixel's colour (restir_shade.comp; docs/ARCHITECTURE.md,
// "The colour control variate"): b = colour_cv k / (k + S), S the spread of the window's initial
// estimates' colours about their common colour w. A shrinkage factor sigma_A^2 / (sigma_A^2 + sigma_B^2)
// with B's colour variance measured by S and A's taken as k (RestirOptions::colour_cv_spread, 0.3:
// chosen offline, docs/BENCHMARKS.md, "The colour control variate"). Shared with the host's tests.
#ifndef STRATA_COLOUR_CV_H
#define STRATA_COLOUR_CV_H
#include "include/lang.h"
#include "material/bsdf.h"

STRATA_NAMESPACE_BEGIN

// Sums over the window's initial estimates B_j, one pass: enough for w and for S.
struct ColourWindow {
  vec3 sum;     // sum_j B_j
  vec3 sum_sq;  // sum_j B_j^2, per channel
  vec3 sum_lb;  // sum_j lum(B_j) B_j
  float sum_l2; // sum_j lum(B_j)^2
  float n;      // pixels
};

INLINE ColourWindow colour_window_empty() {
  ColourWindow c;
  c.sum = vec3(0.0f);
  c.sum_sq = vec3(0.0f);
  c.sum_lb = vec3(0.0f);
  c.sum_l2 = 0.0f;
  c.n = 0.0f;
  return c;
}

INLINE void colour_window_add(INOUT(ColourWindow) c, vec3 b_j) {
  float l = luminance(b_j);
  c.sum += b_j;
  c.sum_sq += b_j * b_j;
  c.sum_lb += l * b_j;
  c.sum_l2 += l * l;
  c.n += 1.0f;
}

// S = n sum_j |B_j - w lum(B_j)|^2 / y^2 with y = lum(sum_j B_j) > 0 and w = sum_j B_j / y (the
// caller's, which it needs for the variate too): the colours' squared spread about w relative to the
// window's mean luminance (0 where every B_j has w's colour). The square is expanded so that the
// sums above suffice.
INLINE float colour_window_spread(ColourWindow c, vec3 w, float y) {
  vec3 s = c.sum_sq - 2.0f * w * c.sum_lb + w * w * c.sum_l2;
  return max(s.r + s.g + s.b, 0.0f) * c.n / (y * y);
}

// k = 0: no shrinkage, b = colour_cv everywhere.
INLINE float colour_cv_b(float colour_cv, float k, float spread) {
  return k > 0.0f ? colour_cv * k / (k + spread) : colour_cv;
}

STRATA_NAMESPACE_END
#endif
