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

// The reconnectability rules (Lin et al. 2022 section 6.2; docs/ARCHITECTURE.md), the one set that
// candidate generation (restir_initial) and every shift (restir/path_vertex.glsl) apply, so that a
// shift is a bijection between paths of the same structure and fails symmetrically.
//
// A vertex is rough enough to take part in a reconnection when its roughness is at least
// RECONNECT_MIN_ALPHA or it has no specular lobe at all (f0 = 0: purely diffuse).
INLINE bool rough_vertex(float alpha, float f0_max) { return alpha >= RECONNECT_MIN_ALPHA || f0_max <= 0.0f; }

// The edge to a reconnection vertex must not be short relative to the primary hit's distance, and
// the vertex must not be seen at a grazing angle (where the reconnection Jacobian is singular).
INLINE bool reconnectable_edge(float edge_length, float camera_distance, float cos_at_vertex) {
  return edge_length >= RECONNECT_MIN_EDGE_RELATIVE * camera_distance && cos_at_vertex >= SHIFT_MIN_COS;
}

// An intermediate vertex x_k may be the reconnection vertex after x_{k-1}.
INLINE bool reconnectable(bool rough_prev, bool rough_k, float edge_length, float camera_distance, float cos_k) {
  return rough_prev && rough_k && reconnectable_edge(edge_length, camera_distance, cos_k);
}

// The path's last vertex needs only a rough x_{n-1} and, on a surface, the edge and angle rule
// (its emission does not depend on the direction); an escaped path only the rough x_{n-1}.
INLINE bool reconnectable_end(bool rough_prev, bool escaped, float edge_length, float camera_distance, float cos_end) {
  return rough_prev && (escaped || reconnectable_edge(edge_length, camera_distance, cos_end));
}

STRATA_NAMESPACE_END
#endif
