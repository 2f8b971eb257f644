// Environment maps as the device sees them, and the equirectangular mapping shared by the host
// (server/scene/environment_map.h, which builds the sampling tables) and the device
// (include/scene_lights.glsl, which samples and evaluates them). One definition for GLSL and C++.
//
// Mapping: u in [0, 1) turns about +Y, v in [0, 1] runs from +Y (v = 0) to -Y. phi = 2 pi (u - 1/2),
// theta = pi v; the direction (before the map's rotation about +Y) is
//   (sin theta sin phi, cos theta, -sin theta cos phi),
// so the image's centre column looks down -Z. The solid angle of UV cell du dv is
// 2 pi^2 sin theta du dv, so a density p(u, v) over UV is p(u, v) / (2 pi^2 sin theta) over
// directions (pbrt-v4, 12.5.2, for the same change of variables).
#ifndef STRATA_ENVIRONMENT_DATA_H
#define STRATA_ENVIRONMENT_DATA_H
#include "include/lang.h"

STRATA_NAMESPACE_BEGIN

// The map's record, at the device address GpuFrameConstants::environment_map (0: no map, the
// constant environment). The three tables are separate allocations of the same buffer, by address:
//   radiance      vec4 per texel, row-major, top row first; rgb = radiance x intensity
//   conditional   per row, width + 1 floats: the CDF over its columns (0 .. 1)
//   marginal      height + 1 floats: the CDF over the rows
struct GpuEnvironmentMap {
  uvec2 radiance;
  uvec2 conditional;
  uvec2 marginal;
  uint width;
  uint height;
  float rotation_cos;  // the map's rotation about +Y (counter-clockwise seen from above)
  float rotation_sin;
  float pad0;
  float pad1;
};

CONST_DEF float ENVIRONMENT_PI = 3.14159265358979323846f;

// World direction of UV (u, v), rotated by (c, s) = (cos, sin) of the map's rotation.
INLINE vec3 environment_map_direction(vec2 uv, float c, float s) {
  float phi = 2.0f * ENVIRONMENT_PI * (uv.x - 0.5f);
  float theta = ENVIRONMENT_PI * uv.y;
  vec3 d = vec3(sin(theta) * sin(phi), cos(theta), -sin(theta) * cos(phi));
  return vec3(c * d.x + s * d.z, d.y, -s * d.x + c * d.z);
}

// UV of a unit world direction (the inverse of environment_map_direction).
INLINE vec2 environment_map_uv(vec3 direction, float c, float s) {
  vec3 d = vec3(c * direction.x - s * direction.z, direction.y, s * direction.x + c * direction.z);
  float u = 0.5f + atan(d.x, -d.z) / (2.0f * ENVIRONMENT_PI);
  float v = acos(clamp(d.y, -1.0f, 1.0f)) / ENVIRONMENT_PI;
  return vec2(u, v);
}

// The texel (column, row) that UV falls in, for a width x height map.
INLINE uvec2 environment_map_texel(vec2 uv, uint width, uint height) {
  uint i = min(uint(max(uv.x, 0.0f) * float(width)), width - 1u);
  uint j = min(uint(max(uv.y, 0.0f) * float(height)), height - 1u);
  return uvec2(i, j);
}

// Solid-angle density of a direction at polar coordinate v whose texel has probability
// p_row p_col: the texel's UV density (p_row p_col width height) over 2 pi^2 sin theta. 0 at the
// poles, where no texel centre lies.
INLINE float environment_map_solid_angle_pdf(float p_texel, uint width, uint height, float v) {
  float sin_theta = sin(ENVIRONMENT_PI * v);
  if (!(sin_theta > 0.0f)) return 0.0f;
  return p_texel * float(width) * float(height) / (2.0f * ENVIRONMENT_PI * ENVIRONMENT_PI * sin_theta);
}

STRATA_NAMESPACE_END

#ifdef __cplusplus
static_assert(sizeof(strata::gpu::GpuEnvironmentMap) == 48);
#endif
#endif
