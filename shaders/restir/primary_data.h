// The visibility buffer (stage `primary`): per pixel, the hit of one camera ray, as the scene
// bridge's RayHit reports it, with the LoD level of the instance it hit and the camera sample of
// the ray. Which ray is GpuFrameConstants::primary_mode's choice: PRIMARY_CENTRE, through the pixel
// centre and the lens centre at the frame's instant (the splat methods, the disocclusion mask);
// PRIMARY_DOMAIN, the pixel's camera sample of this frame, which fixes the primary vertex of the
// pixel's domain (the gather methods: docs/ARCHITECTURE.md, "Domains and their primary vertex").
// Temporal gather, splatting, the spatial filter and the disocclusion mask read it instead of
// tracing that ray again. 48 bytes.
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
  vec2 jitter;     // the camera sample: subpixel position in [0,1)^2 (box filter),
  uint lens;       // lens sample as unorm16 x 2 (packUnorm2x16, as a path sample keeps it),
  float time;      // and shutter time in [0,1)
};

STRATA_NAMESPACE_END

#ifdef __cplusplus
static_assert(sizeof(strata::gpu::GpuPrimaryHit) == 48);
#endif
#endif
