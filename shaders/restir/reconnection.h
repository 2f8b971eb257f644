// The reconnection shift (Lehtinen et al. 2013; Lin et al. 2022 section 5): the offset path keeps
// the base path's vertex x_k and everything after it, and connects to it from its own y_{k-1}.
// Solid-angle parametrisation: the Jacobian of x_k's incoming direction is
//   |dT/dx| = (|cos theta_y| / |cos theta_x|) * (|x_k - x_{k-1}|^2 / |x_k - y_{k-1}|^2)
// with theta the angle at x_k between its normal and the edge to the previous vertex.
#ifndef STRATA_RESTIR_RECONNECTION_H
#define STRATA_RESTIR_RECONNECTION_H
#include "include/lang.h"
#include "restir/thresholds.h"

STRATA_NAMESPACE_BEGIN

// 0 when the shift must fail: grazing angles, coincident vertices, or a Jacobian outside
// [1/SHIFT_MAX_JACOBIAN, SHIFT_MAX_JACOBIAN].
INLINE float reconnection_jacobian(vec3 x_k, vec3 n_k, vec3 base_prev, vec3 offset_prev) {
  vec3 ex = base_prev - x_k;
  vec3 ey = offset_prev - x_k;
  float dx2 = dot(ex, ex);
  float dy2 = dot(ey, ey);
  if (!(dx2 > 0.0f) || !(dy2 > 0.0f)) return 0.0f;
  float cos_x = abs(dot(n_k, ex)) * inversesqrt(dx2);
  float cos_y = abs(dot(n_k, ey)) * inversesqrt(dy2);
  if (cos_x < SHIFT_MIN_COS || cos_y < SHIFT_MIN_COS) return 0.0f;
  float j = (cos_y / cos_x) * (dx2 / dy2);
  if (!(j >= 1.0f / SHIFT_MAX_JACOBIAN && j <= SHIFT_MAX_JACOBIAN)) return 0.0f;
  return j;
}

// A vertex pair may reconnect when both ends are rough enough and the edge is long enough
// relative to the distance from the camera (DESIGN.md section 6).
INLINE bool reconnectable(float alpha_prev, float alpha_k, float edge_length, float camera_distance) {
  return alpha_prev >= RECONNECT_MIN_ALPHA && alpha_k >= RECONNECT_MIN_ALPHA &&
         edge_length >= RECONNECT_MIN_EDGE_RELATIVE * camera_distance;
}

STRATA_NAMESPACE_END
#endif
