// Rays in and hits out of the ray_probe pass.
#ifndef STRATA_PROBE_DATA_H
#define STRATA_PROBE_DATA_H
#include "include/lang.h"
#include "include/frame_data.h"

STRATA_NAMESPACE_BEGIN

struct GpuProbeRay {
  vec4 origin_tmin;  // render space
  vec4 dir_tmax;
};

struct GpuProbeHit {
  float t;           // < 0: miss
  uint instance;
  uint geometry;
  uint triangle;
  vec2 bary;
  vec2 pad;
};

STRATA_NAMESPACE_END

#ifdef __cplusplus
static_assert(sizeof(strata::gpu::GpuProbeRay) == 32);
static_assert(sizeof(strata::gpu::GpuProbeHit) == 32);
#endif
#endif
