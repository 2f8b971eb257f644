// Textures and alpha-tested materials as the device sees them; one definition for GLSL (std430) and
// C++ (render/scene_textures.cpp uploads them). Bound only for scenes with textures or alpha-tested
// materials, to the passes' textured variants (compiled with STRATA_TEXTURES: include/textures.glsl).
// Texels are the host's TextureSet (scene/scene.h) in its order, every mip level of every image in
// one array, as linear RGBA16 (sRGB decoded on upload: render/scene_textures.cpp), filtered in the
// shader (include/textures.glsl), so that one storage buffer holds every texture whatever their
// number and sizes.
#ifndef STRATA_TEXTURE_DATA_H
#define STRATA_TEXTURE_DATA_H
#include "include/lang.h"

STRATA_NAMESPACE_BEGIN

// GpuTexture::sampling bits: the glTF sampler.
CONST_DEF uint TEXTURE_MAG_LINEAR = 1u;   // else nearest
CONST_DEF uint TEXTURE_MIN_LINEAR = 2u;   // else nearest
CONST_DEF uint TEXTURE_MIP_SHIFT = 2u;    // 2 bits: TEXTURE_MIP_*
CONST_DEF uint TEXTURE_MIP_NONE = 0u;     // level 0 only
CONST_DEF uint TEXTURE_MIP_NEAREST = 1u;
CONST_DEF uint TEXTURE_MIP_LINEAR = 2u;
CONST_DEF uint TEXTURE_WRAP_U_SHIFT = 4u;  // 2 bits each: TEXTURE_WRAP_*
CONST_DEF uint TEXTURE_WRAP_V_SHIFT = 6u;
CONST_DEF uint TEXTURE_WRAP_REPEAT = 0u;
CONST_DEF uint TEXTURE_WRAP_CLAMP = 1u;
CONST_DEF uint TEXTURE_WRAP_MIRROR = 2u;

struct GpuTexture {
  uint first_level;  // into the level table
  uint level_count;
  uint sampling;     // TEXTURE_* bits
  uint pad0;
};

// One mip level: width x height texels at texels[offset], row-major, top row first.
struct GpuMipLevel {
  uint width;
  uint height;
  uint offset;
  uint pad0;
};

// A material's use of a texture: uv' = (dot(row0.xyz, (uv, 1)), dot(row1.xyz, (uv, 1))) of the
// texCoord set `tex_coord` (KHR_texture_transform; the identity without it).
struct GpuTextureRef {
  vec4 row0;
  vec4 row1;
  int texture;    // -1: none
  uint tex_coord;  // 0 or 1
  uint pad0;
  uint pad1;
};

CONST_DEF uint ALPHA_OPAQUE = 0u;
CONST_DEF uint ALPHA_MASK = 1u;  // glTF MASK, and BLEND rendered as MASK at cutoff 0.5
// GpuMaterialTextures::flags
CONST_DEF uint MATERIAL_VERTEX_EXTRAS = 1u;  // the scene's vertices have GpuVertexExtra records

// GpuMaterialTextures::slots: a material's textures by what they hold.
CONST_DEF uint MATERIAL_TEXTURE_BASE_COLOR = 0u;          // sRGB RGB x base colour factor; alpha x the factor's alpha
CONST_DEF uint MATERIAL_TEXTURE_METALLIC_ROUGHNESS = 1u;  // B x metallic, G x roughness
CONST_DEF uint MATERIAL_TEXTURE_EMISSIVE = 2u;            // sRGB RGB x emission
CONST_DEF uint MATERIAL_TEXTURE_NORMAL = 3u;              // tangent space, xy x normal_scale
CONST_DEF uint MATERIAL_TEXTURE_SLOTS = 4u;
// The slots material_at reads (GpuMaterialTextures::textures bits); the normal map is read by the
// hit's shading normal.
CONST_DEF uint MATERIAL_SHADING_TEXTURES = (1u << MATERIAL_TEXTURE_BASE_COLOR) | (1u << MATERIAL_TEXTURE_METALLIC_ROUGHNESS) |
                                           (1u << MATERIAL_TEXTURE_EMISSIVE);

// Per material, beside GpuMaterial (scene_data.h). The shaders read its fields in place
// (b_material_textures[m].slots[k]), never a copy of the whole record: on lavapipe every load is
// compiled again at every inlined call site, and a slot indexed at run time is one load.
struct GpuMaterialTextures {
  GpuTextureRef slots[4];            // MATERIAL_TEXTURE_*
  float alpha;                       // baseColorFactor alpha
  float alpha_cutoff;
  uint alpha_mode;                   // ALPHA_*
  float normal_scale;
  uint flags;                        // MATERIAL_VERTEX_EXTRAS
  uint textures;                     // bit k: slots[k] has a texture
  uint pad0;
  uint pad1;
};

// Per vertex (the same index as GpuVertex), for scenes whose primitives have a second UV set or
// TANGENT: object-space tangent with the bitangent's sign in w (w = 0: none, tangents follow from
// the UVs per triangle), and TEXCOORD_1 in uv1.xy.
struct GpuVertexExtra {
  vec4 tangent;
  vec4 uv1;
};

STRATA_NAMESPACE_END

#ifdef __cplusplus
static_assert(sizeof(strata::gpu::GpuTexture) == 16);
static_assert(sizeof(strata::gpu::GpuMipLevel) == 16);
static_assert(sizeof(strata::gpu::GpuTextureRef) == 48);
static_assert(sizeof(strata::gpu::GpuMaterialTextures) == 4 * 48 + 32);
static_assert(sizeof(strata::gpu::GpuVertexExtra) == 32);
#endif
#endif
