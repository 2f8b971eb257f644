// Scene data as the device sees it; one definition for GLSL (std430) and C++.
// All positions are in render space: world space shifted so that the camera is at the origin
// (docs/ARCHITECTURE.md, Robustness: positions are camera-relative where precision matters).
#ifndef STRATA_SCENE_DATA_H
#define STRATA_SCENE_DATA_H
#include "include/lang.h"

STRATA_NAMESPACE_BEGIN

// Position with u in w, normal with v in w: 32 bytes, object space.
struct GpuVertex {
  vec4 position_u;
  vec4 normal_v;
};

// One glTF primitive of one mesh LoD: triangles [index_offset, index_offset + 3 * triangle_count).
struct GpuPrimitive {
  uint vertex_offset;
  uint index_offset;
  uint triangle_count;
  uint material;
};

// One instance in the TLAS (instance custom index = its position in the instance array).
// A ray-query hit gives geometry index g: the primitive is primitives[primitive_base + g].
struct GpuInstance {
  mat4 object_to_render;
  mat4 normal_to_render;  // inverse transpose of the upper 3x3, padded
  uint primitive_base;
  uint lod;
  uint mesh;
  uint flags;             // INSTANCE_FLAG_* and INSTANCE_CHANGED_*
};

CONST_DEF uint INSTANCE_FLAG_MIRRORED = 1u;  // negative determinant: front faces wind clockwise
// Per-instance change tracking: what changed between the previous frame and this one, in this
// frame's record, so that a shift can ask about exactly the instances it touches. All zero on a
// session's first frame.
CONST_DEF uint INSTANCE_CHANGED_TRANSFORM = 2u;  // its object-to-world transform
CONST_DEF uint INSTANCE_CHANGED_LOD = 4u;        // its LoD level (another mesh, another topology)
CONST_DEF uint INSTANCE_CHANGED_EMISSION = 8u;   // it emits and moved or switched level: the light it casts changed
CONST_DEF uint INSTANCE_CHANGED_SHAPE = 16u;     // it deforms and its joints or morph weights changed: its vertices moved
CONST_DEF uint INSTANCE_CHANGED = 30u;           // any of the above

// The swept boxes of change tracking (docs/ARCHITECTURE.md, "Suffix replay"): for every instance
// that changed since the previous frame, a render-space box (of this frame) holding its geometry in
// both frames, so that a ray missing every box meets the same unchanged surfaces in both. With more
// changed instances than SWEPT_BOXES_MAX, `count` exceeds it and every ray counts as meeting one.
CONST_DEF uint SWEPT_BOXES_MAX = 64u;
struct GpuSweptBoxes {
  vec4 prev_to_current;  // xyz: a point of the previous frame's render space plus this is in this one's
  uint count;            // changed instances (> SWEPT_BOXES_MAX: too many to list)
  uint pad0;
  uint pad1;
  uint pad2;
  vec4 lo[SWEPT_BOXES_MAX];  // xyz: the box's lower corner
  vec4 hi[SWEPT_BOXES_MAX];  // xyz: its upper corner
};

CONST_DEF uint MATERIAL_DOUBLE_SIDED = 1u;

struct GpuMaterial {
  vec4 base_color_metallic;    // rgb base colour, a metallic
  vec4 emission_roughness;     // rgb emitted radiance, a perceptual roughness
  float specular;              // KHR_materials_specular factor: dielectric F0 = 0.04 * specular
  uint flags;
  uint pad0;
  uint pad1;
};

// A world-space emissive triangle for next-event estimation, in render space.
struct GpuEmitter {
  vec4 p0_area;       // p0, triangle area
  vec4 p1_pmf;        // p1, probability of choosing this emitter (power / total power)
  vec4 p2_flags;      // p2, flags as float bits (MATERIAL_DOUBLE_SIDED)
  vec4 emission;      // rgb radiance
  uvec4 surface;      // instance, geometry (primitive of its mesh), triangle, 1 if p1/p2 were swapped (re-wound)
};

// A KHR_lights_punctual light as the frame has it, in render space (include/scene_lights.glsl). The
// light table is the emissive triangles followed by these, one alias table over both: entry
// emitter_count + i of the table is punctual light i (the scene's light index, the same every frame).
// Units (scene/scene.h): point and spot intensity I gives irradiance I / d^2 facing the light; a
// directional light's intensity is the irradiance facing it.
CONST_DEF uint PUNCTUAL_DIRECTIONAL = 0u;
CONST_DEF uint PUNCTUAL_POINT = 1u;
CONST_DEF uint PUNCTUAL_SPOT = 2u;
struct GpuPunctualLight {
  vec4 position_range;   // xyz render-space position (point, spot), w range (0: unlimited)
  vec4 direction_type;   // xyz unit direction the light shines (spot, directional), w PUNCTUAL_* as a float
  vec4 intensity_pmf;    // rgb colour x intensity, w probability that the light table picks this light
  vec4 cone;             // spot: x light angle scale, y light angle offset (KHR_lights_punctual's reference); zw 0
};

// Walker/Vose alias table entry over emitters.
struct GpuAliasEntry {
  float threshold;
  uint alias;
  uint pad0;
  uint pad1;
};

STRATA_NAMESPACE_END

#ifdef __cplusplus
static_assert(sizeof(strata::gpu::GpuVertex) == 32);
static_assert(sizeof(strata::gpu::GpuPrimitive) == 16);
static_assert(sizeof(strata::gpu::GpuInstance) == 144);
static_assert(sizeof(strata::gpu::GpuMaterial) == 48);
static_assert(sizeof(strata::gpu::GpuEmitter) == 80);
static_assert(sizeof(strata::gpu::GpuAliasEntry) == 16);
static_assert(sizeof(strata::gpu::GpuPunctualLight) == 64);
static_assert(sizeof(strata::gpu::GpuSweptBoxes) == 32 + 32 * strata::gpu::SWEPT_BOXES_MAX);
#endif
#endif
