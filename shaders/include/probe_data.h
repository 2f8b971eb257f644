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
  uint lod;          // LoD level in the instance record of the traced slot (the record moves with the TLAS)
  uint pad;
};

// Specialization constant of ray_probe: trace the previous frame's slot (BINDING_TLAS_PREV and
// BINDING_INSTANCES_PREV) instead of the current one.
#define PROBE_SPEC_PREVIOUS 0

STRATA_NAMESPACE_END

#ifdef __cplusplus
static_assert(sizeof(strata::gpu::GpuProbeRay) == 32);
static_assert(sizeof(strata::gpu::GpuProbeHit) == 32);
#endif
#endif
