// The reprojection Jacobian of reservoir splatting (RS-main 4.1.3). A primary hit x1 that moves
// with its object to y1 and is seen from a new camera changes its subpixel location from v to u:
//   |du/dv| = |du/dy1| |dy1/dx1| |dx1/dv|                                   (RS-main Eq. 14)
//   |dy1/du| = |dy1/dw| |dw/du| = |y1 - y0|^2 / cos theta_N * cos^3 theta_V   (RS-main Eq. 15)
// (a unit image-plane area at angle theta_V from the axis subtends cos^3 theta_V of solid angle),
// so the subpixel factor of RS-main Eq. 16 is
//   (cos theta_N cos^3 theta_V^prev |x1 - x0|^2) / (cos theta_N^prev cos^3 theta_V |y1 - y0|^2)
// times |dy1/dx1| (1 for rigid motion, else the ratio of the triangle's current to prior area).
#ifndef STRATA_RESTIR_REPROJECTION_H
#define STRATA_RESTIR_REPROJECTION_H
#include "include/lang.h"
#include "restir/thresholds.h"

STRATA_NAMESPACE_BEGIN

struct PrimaryView {
  float distance_sq;  // |x1 - x0|^2
  float cos_normal;   // |cos| between the hit normal and the direction to the camera
  float cos_view;     // cos between the camera's forward vector and the direction to the hit
};

INLINE PrimaryView primary_view(vec3 hit, vec3 normal, vec3 camera, vec3 forward) {
  PrimaryView v;
  vec3 d = hit - camera;
  v.distance_sq = dot(d, d);
  float inv = v.distance_sq > 0.0f ? inversesqrt(v.distance_sq) : 0.0f;
  v.cos_normal = abs(dot(normal, d)) * inv;
  v.cos_view = dot(forward, d) * inv;
  return v;
}

// |du/dv| of RS-main Eq. 16 without the path-suffix factor; 0 when a cosine is grazing or the
// point is behind a camera (the shift fails).
INLINE float reprojection_jacobian(PrimaryView prev, PrimaryView cur, float area_ratio) {
  if (prev.cos_normal < SHIFT_MIN_COS || cur.cos_normal < SHIFT_MIN_COS) return 0.0f;
  if (prev.cos_view < SHIFT_MIN_COS || cur.cos_view < SHIFT_MIN_COS) return 0.0f;
  if (!(prev.distance_sq > 0.0f) || !(cur.distance_sq > 0.0f)) return 0.0f;
  float cv_prev3 = prev.cos_view * prev.cos_view * prev.cos_view;
  float cv_cur3 = cur.cos_view * cur.cos_view * cur.cos_view;
  float j = (cur.cos_normal * cv_prev3 * prev.distance_sq) / (prev.cos_normal * cv_cur3 * cur.distance_sq) * area_ratio;
  if (!(j >= 1.0f / SHIFT_MAX_JACOBIAN && j <= SHIFT_MAX_JACOBIAN)) return 0.0f;
  return j;
}

// Image-plane area per unit subpixel area of a camera whose image has w x h pixels: the factor of
// |dw/du| that Eq. 15 leaves out because it cancels while field of view and resolution stay fixed.
// `right` and `up` span the image plane at unit distance along the view axis (GpuCamera).
INLINE float pixel_area(vec3 right, vec3 up, uint w, uint h) {
  return 4.0f * length(right) * length(up) / (float(w) * float(h));
}

// The same with the pixel areas of both frames, exact under zoom and resolution changes.
INLINE float reprojection_jacobian(PrimaryView prev, PrimaryView cur, float area_ratio, float pixel_area_prev, float pixel_area_cur) {
  if (!(pixel_area_prev > 0.0f) || !(pixel_area_cur > 0.0f)) return 0.0f;
  return reprojection_jacobian(prev, cur, area_ratio * pixel_area_prev / pixel_area_cur);
}

STRATA_NAMESPACE_END
#endif
