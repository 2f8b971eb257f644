// Robust ray origins: Waechter & Binder, "A Fast and Robust Method for Avoiding Self-Intersection",
// Ray Tracing Gems (2019), ch. 6. The offset is a few ulps along the normal in integer space, so it
// scales with the magnitude of the position (geometry far from the origin stays correct).
#ifndef STRATA_RAY_OFFSET_H
#define STRATA_RAY_OFFSET_H
#include "include/lang.h"

STRATA_NAMESPACE_BEGIN

CONST_DEF float RAY_OFFSET_ORIGIN = 1.0f / 32.0f;
CONST_DEF float RAY_OFFSET_FLOAT_SCALE = 1.0f / 65536.0f;
CONST_DEF float RAY_OFFSET_INT_SCALE = 256.0f;
// Visibility rays stop this fraction short of their target (docs/ARCHITECTURE.md, Robustness).
CONST_DEF float SHADOW_RAY_SHORTEN = 1e-4f;
// The t_max of a ray without an end (a camera, BSDF or environment ray: its closest hit, or none):
// farther than anything a scene holds. Also the far end of the front layer's depth range.
CONST_DEF float RAY_UNBOUNDED = 1e30f;

INLINE float offset_component(float p, float n) {
  // Near the origin a float offset; elsewhere a few ulps in integer space. The integer path only
  // runs for |p| >= 1/32, whose bit patterns are far from INT_MIN/INT_MAX (no overflow, even as C++).
  if (abs(p) < RAY_OFFSET_ORIGIN) return p + RAY_OFFSET_FLOAT_SCALE * n;
  int of_i = int(RAY_OFFSET_INT_SCALE * n);
  return intBitsToFloat(floatBitsToInt(p) + (p < 0.0f ? -of_i : of_i));
}

// p: hit position, n: geometric normal on the side the new ray leaves from.
INLINE vec3 offset_ray_origin(vec3 p, vec3 n) {
  return vec3(offset_component(p.x, n.x), offset_component(p.y, n.y), offset_component(p.z, n.z));
}

// The direction and distance from a spawn origin (offset_ray_origin of a surface point) to the
// point `target` that a visibility ray tests (a point on a light, a reconnection vertex): aimed
// from the origin itself. Aimed from the surface point instead, a ray started at the offset origin
// crosses the target's surface short of the target by the offset's share along the target's
// normal, and where that exceeds SHADOW_RAY_SHORTEN the ray hits the target's own surface: the
// offset is 256 ulps of the origin's coordinates (about 3e-5 of its distance from the render-space
// origin, the camera), so next-event estimation missed lights nearer to a surface than about a
// third of the surface's distance from the camera. False where the target is the origin.
INLINE bool aim_ray(vec3 origin, vec3 target, OUT(vec3) dir, OUT(float) dist) {
  vec3 to = target - origin;
  dist = length(to);
  dir = vec3(0.0f, 0.0f, 1.0f);
  if (!(dist > 0.0f) || isinf(dist)) return false;
  dir = to / dist;
  return true;
}

// The visibility ray from spawn origin `origin` of the surface point `from` to what lies `dist`
// along the unit `dir` from it: aimed at that point from the origin (aim_ray) and SHADOW_RAY_SHORTEN
// short of it, or, for an infinite `dist` (the environment, a directional light), along `dir`
// without end. False where the point is the origin.
INLINE bool visibility_ray(vec3 origin, vec3 from, vec3 dir, float dist, OUT(vec3) aim, OUT(float) t_max) {
  aim = dir;
  t_max = RAY_UNBOUNDED;
  if (isinf(dist)) return true;
  if (!aim_ray(origin, from + dir * dist, aim, t_max)) return false;
  t_max *= 1.0f - SHADOW_RAY_SHORTEN;
  return true;
}

STRATA_NAMESPACE_END
#endif
