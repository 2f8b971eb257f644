// The visibility buffer (stage `primary`): per pixel, the hit of one camera ray, as the scene
// bridge's RayHit reports it, with the LoD level of the instance it hit and the camera sample of
// the ray. Which ray is GpuFrameConstants::primary_mode's choice: PRIMARY_CENTRE, through the pixel
// centre and the lens centre at the frame's instant (the splat methods, the disocclusion mask);
// PRIMARY_DOMAIN, the pixel's camera sample of this frame, which fixes the primary vertex of the
// pixel's domain (the gather methods: docs/ARCHITECTURE.md, "Domains and their primary vertex").
// Temporal gather, splatting, the spatial filter and the disocclusion mask read it instead of
// tracing that ray again.
//
// With the hit, the entry keeps its surface as the scene bridge loads it in the entry's frame
// (position, normals, area, material: scene_bridge.glsl, SurfaceHit) and the material's kind
// (restir/centre_surface.glsl). Every reuse stage reads a pixel's primary vertex many times (each
// shift into the domain, each neighbour the spatial filter looks at, the temporal filter's previous
// pixel), and loading it from the mesh (instance, primitive, three vertices, transforms) costs
// several times more than reading the entry on lavapipe, where a per-pixel load is a gather. The previous
// frame's entries hold the previous frame's surfaces, which is what the previous frame's instance
// records would give. 96 bytes.
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
  // The hit's surface in the entry's frame (zero without a hit), for primary_surface_hit():
  vec4 position_area;        // render-space position, triangle area
  vec4 geo_normal_material;  // geometric normal, material index (its bits)
  vec4 shading_normal_kind;  // shading normal, SURFACE_KIND_* bits of the material (their bits)
};

// With fixed primary vertices in a textured scene, per visibility-buffer entry (the same index):
// the factors of its material at its primary footprint, as material_factors gave them to the
// primary stage (include/scene_bridge.glsl, MaterialFactors). The initial pass and every shift into
// the domain read its primary vertex's material here (restir/restir_pass.glsl,
// fixed_primary_material) instead of filtering its textures again.
struct GpuPrimaryMaterial {
  vec4 base_color_metallic;
  vec4 emission_roughness;
};

STRATA_NAMESPACE_END

#ifdef __cplusplus
static_assert(sizeof(strata::gpu::GpuPrimaryHit) == 96);
static_assert(sizeof(strata::gpu::GpuPrimaryMaterial) == 32);
#endif
#endif
