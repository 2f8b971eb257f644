// Warps from [0,1)^2 to the domains the path tracer samples, each with its density.
#ifndef STRATA_WARP_H
#define STRATA_WARP_H
#include "include/lang.h"

STRATA_NAMESPACE_BEGIN

CONST_DEF float PI = 3.14159265358979323846f;
CONST_DEF float INV_PI = 0.31830988618379067154f;

// Shirley-Chiu concentric map to the unit disk (area-preserving, density 1/pi).
INLINE vec2 sample_concentric_disk(vec2 u) {
  vec2 o = 2.0f * u - vec2(1.0f);
  if (o.x == 0.0f && o.y == 0.0f) return vec2(0.0f);
  float r;
  float theta;
  if (abs(o.x) > abs(o.y)) {
    r = o.x;
    theta = (PI / 4.0f) * (o.y / o.x);
  } else {
    r = o.y;
    theta = (PI / 2.0f) - (PI / 4.0f) * (o.x / o.y);
  }
  return r * vec2(cos(theta), sin(theta));
}

// Cosine-weighted hemisphere around +z: density cos(theta) / pi.
INLINE vec3 sample_cosine_hemisphere(vec2 u) {
  vec2 d = sample_concentric_disk(u);
  float z = sqrt(max(0.0f, 1.0f - d.x * d.x - d.y * d.y));
  return vec3(d.x, d.y, z);
}

// Uniform direction on the sphere: density 1 / (4 pi).
INLINE vec3 sample_uniform_sphere(vec2 u) {
  float z = 1.0f - 2.0f * u.x;
  float r = sqrt(max(0.0f, 1.0f - z * z));
  float phi = 2.0f * PI * u.y;
  return vec3(r * cos(phi), r * sin(phi), z);
}

// Uniform point on a triangle as barycentrics (b1, b2) (Heitz 2019 low-distortion map is not
// needed here; the square-root map is exact): density 1 / area.
INLINE vec2 sample_triangle_barycentrics(vec2 u) {
  float su = sqrt(u.x);
  return vec2(1.0f - su, u.y * su);
}

// Orthonormal basis around a unit normal (Duff et al. 2017, branchless).
INLINE void make_onb(vec3 n, OUT(vec3) t, OUT(vec3) b) {
  float s = n.z >= 0.0f ? 1.0f : -1.0f;
  float a = -1.0f / (s + n.z);
  float c = n.x * n.y * a;
  t = vec3(1.0f + s * n.x * n.x * a, s * c, -s * n.x);
  b = vec3(c, s + n.y * n.y * a, -n.y);
}

INLINE vec3 to_world(vec3 v, vec3 t, vec3 b, vec3 n) { return v.x * t + v.y * b + v.z * n; }
INLINE vec3 to_local(vec3 v, vec3 t, vec3 b, vec3 n) { return vec3(dot(v, t), dot(v, b), dot(v, n)); }

// Converts an area density at a surface point to a solid-angle density seen from another point.
// Returns 0 (the sample is unusable) for grazing or coincident points instead of dividing by ~0.
INLINE float area_to_solid_angle_pdf(float pdf_area, float distance_sq, float cos_at_surface) {
  float c = abs(cos_at_surface);
  if (c < 1e-7f || !(distance_sq > 0.0f)) return 0.0f;
  return pdf_area * distance_sq / c;
}

STRATA_NAMESPACE_END
#endif
