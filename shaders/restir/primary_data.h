// The visibility buffer (stage `primary`): per pixel, the hit of the ray through the pixel centre
// and the lens centre at the frame's instant, as the scene bridge's RayHit reports it, with the
// LoD level of the instance it hit. Temporal gather, splatting and the disocclusion mask read it
// instead of tracing that ray again. 32 bytes.
#ifndef STRATA_PRIMARY_DATA_H
#define STRATA_PRIMARY_DATA_H
#include "include/lang.h"

STRATA_NAMESPACE_BEGIN

CONST_DEF uint PRIMARY_HIT = 1u;  // flags: the ray hit a surface (else every other field is 0)

struct GpuPrimaryHit {
  float t;
  uint instance;
  uint geometry;   // primitive of the instance's mesh
  uint triangle;
  vec2 bary;       // barycentrics of vertices 1 and 2
  uint lod;        // the instance's LoD level in that frame
  uint flags;      // PRIMARY_*
};

STRATA_NAMESPACE_END

#ifdef __cplusplus
static_assert(sizeof(strata::gpu::GpuPrimaryHit) == 32);
#endif
#endif
