// Texture lookups of the scene bridge (include/scene_bridge.glsl includes this file in the passes'
// textured variants, compiled with STRATA_TEXTURES; nothing else includes it). Texels are RGBA8
// words in one storage buffer (include/texture_data.h) and are filtered here: sRGB texels are
// decoded to linear before they are weighted, wrap modes are applied per texel, and the mip level
// follows from a footprint width in UV units (the scene bridge's footprint rule: material_at).
#ifndef STRATA_TEXTURES_GLSL
#define STRATA_TEXTURES_GLSL

#include "include/bindings.h"
#include "include/texture_data.h"

layout(set = 0, binding = BINDING_MATERIAL_TEXTURES, std430) readonly buffer MaterialTextures { GpuMaterialTextures b_material_textures[]; };
layout(set = 0, binding = BINDING_TEXTURES, std430) readonly buffer Textures { GpuTexture b_textures[]; };
layout(set = 0, binding = BINDING_TEXTURE_LEVELS, std430) readonly buffer TextureLevels { GpuMipLevel b_texture_levels[]; };
layout(set = 0, binding = BINDING_TEXELS, std430) readonly buffer Texels { uint b_texels[]; };
layout(set = 0, binding = BINDING_VERTEX_EXTRAS, std430) readonly buffer VertexExtras { GpuVertexExtra b_vertex_extras[]; };
// Per triangle (its first index / 3): the emission light sampling selects it by (render/scene_textures.h,
// triangle_light_emission), read for materials with an emissive texture only.
layout(set = 0, binding = BINDING_LIGHT_EMISSION, std430) readonly buffer LightEmission { vec4 b_light_emission[]; };

// IEC 61966-2-1, as scene/texture_mips.cpp decodes when it builds the chains.
vec3 srgb_to_linear(vec3 c) {
  return mix(c * (1.0 / 12.92), pow((c + 0.055) * (1.0 / 1.055), vec3(2.4)), greaterThan(c, vec3(0.04045)));
}

// A texel index wrapped into [0, n): i lies in [-1, 2n] (sample_texture folds UVs into one period
// of every wrap mode, [0, 2] for repeat and mirror repeat, [-1, 2] for clamp), so that a
// compare and an add or subtract wrap it. An integer remainder would be exact too, but a vector
// remainder is a scalar division per lane on a CPU device.
int wrap_texel(int i, int n, uint mode) {
  if (mode == TEXTURE_WRAP_CLAMP) return clamp(i, 0, n - 1);
  int period = 2 * n;
  int m = i < 0 ? i + period : (i >= period ? i - period : i);  // i mod 2n
  if (mode == TEXTURE_WRAP_MIRROR) return m < n ? m : period - 1 - m;
  return m >= n ? m - n : m;
}

// A texel, its RGB decoded to linear where `sampling` has TEXTURE_SRGB.
vec4 texel_at(GpuMipLevel l, uint x, uint y, uint sampling) {
  vec4 c = unpackUnorm4x8(b_texels[l.offset + y * l.width + x]);
  if ((sampling & TEXTURE_SRGB) != 0u) c.rgb = srgb_to_linear(c.rgb);
  return c;
}

// One level at uv (texel centres at half-integers, as Vulkan samples), nearest or bilinear; each
// axis's texel indices are wrapped once for the texels that share them.
vec4 sample_level(uint level, vec2 uv, bool linear, uint sampling) {
  GpuMipLevel l = b_texture_levels[level];
  ivec2 n = ivec2(l.width, l.height);
  uint wrap_u = (sampling >> TEXTURE_WRAP_U_SHIFT) & 3u;
  uint wrap_v = (sampling >> TEXTURE_WRAP_V_SHIFT) & 3u;
  vec2 p = uv * vec2(n);
  if (!linear) {
    ivec2 i = ivec2(floor(p));
    return texel_at(l, uint(wrap_texel(i.x, n.x, wrap_u)), uint(wrap_texel(i.y, n.y, wrap_v)), sampling);
  }
  p -= 0.5;
  vec2 f = floor(p);
  ivec2 i = ivec2(f);
  f = p - f;
  uint x0 = uint(wrap_texel(i.x, n.x, wrap_u));
  uint x1 = uint(wrap_texel(i.x + 1, n.x, wrap_u));
  uint y0 = uint(wrap_texel(i.y, n.y, wrap_v));
  uint y1 = uint(wrap_texel(i.y + 1, n.y, wrap_v));
  vec4 a = mix(texel_at(l, x0, y0, sampling), texel_at(l, x1, y0, sampling), f.x);
  vec4 b = mix(texel_at(l, x0, y1, sampling), texel_at(l, x1, y1, sampling), f.x);
  return mix(a, b, f.y);
}

// Texture `t` at uv with a footprint `width_uv` wide in UV units (0: the finest level). The level
// of detail is log2 of the footprint in level-0 texels (Akenine-Moeller et al. 2019, "Texture Level
// of Detail Strategies for Real-Time Ray Tracing", Eq. 34 with the width already projected); at
// or below 0 the magnification filter reads level 0, above it the minification filter reads the
// level(s) the sampler's mipmap mode picks. `alpha_only`: only the alpha channel is wanted (the RGB
// returned is then not decoded from sRGB).
vec4 sample_texture(uint t, vec2 uv, float width_uv, bool alpha_only) {
  GpuTexture tex = b_textures[t];
  if (alpha_only) tex.sampling &= ~TEXTURE_SRGB;
  // A non-finite UV reads the first texel; a finite one is folded into one period of every wrap mode
  // (repeat and mirror repeat over 2, clamp just outside [0, 1]) so that texel indices stay small.
  if (any(isnan(uv)) || any(isinf(uv))) uv = vec2(0.0);
  vec2 folded = uv - 2.0 * floor(uv * 0.5);
  vec2 clamped = clamp(uv, vec2(-1.0), vec2(2.0));
  uv.x = ((tex.sampling >> TEXTURE_WRAP_U_SHIFT) & 3u) == TEXTURE_WRAP_CLAMP ? clamped.x : folded.x;
  uv.y = ((tex.sampling >> TEXTURE_WRAP_V_SHIFT) & 3u) == TEXTURE_WRAP_CLAMP ? clamped.y : folded.y;
  GpuMipLevel base = b_texture_levels[tex.first_level];
  float texels = width_uv * sqrt(float(base.width) * float(base.height));
  float lambda = texels > 0.0 ? log2(texels) : -1.0;
  if (!(lambda > 0.0)) return sample_level(tex.first_level, uv, (tex.sampling & TEXTURE_MAG_LINEAR) != 0u, tex.sampling);
  bool min_linear = (tex.sampling & TEXTURE_MIN_LINEAR) != 0u;
  uint mip = (tex.sampling >> TEXTURE_MIP_SHIFT) & 3u;
  float last = float(tex.level_count - 1u);
  lambda = min(lambda, last);
  if (mip == TEXTURE_MIP_NONE) return sample_level(tex.first_level, uv, min_linear, tex.sampling);
  if (mip == TEXTURE_MIP_NEAREST) return sample_level(tex.first_level + uint(floor(lambda + 0.5)), uv, min_linear, tex.sampling);
  float lo = floor(lambda);
  vec4 a = sample_level(tex.first_level + uint(lo), uv, min_linear, tex.sampling);
  if (lambda == lo) return a;
  return mix(a, sample_level(tex.first_level + uint(lo) + 1u, uv, min_linear, tex.sampling), lambda - lo);
}

// A material's texture at a surface whose texCoord sets are `uv` (xy set 0, zw set 1) with
// `density` UV units per render-space unit (x set 0, y set 1), for a footprint `width` wide in
// render space. KHR_texture_transform moves the UV and scales the footprint with it.
vec4 sample_texture_ref(GpuTextureRef r, vec4 uv, vec2 density, float width, bool alpha_only) {
  vec2 t = r.tex_coord == 1u ? uv.zw : uv.xy;
  float d = r.tex_coord == 1u ? density.y : density.x;
  vec2 tuv = vec2(dot(r.row0.xyz, vec3(t, 1.0)), dot(r.row1.xyz, vec3(t, 1.0)));
  float scale = sqrt(abs(r.row0.x * r.row1.y - r.row0.y * r.row1.x));
  return sample_texture(uint(r.texture), tuv, width * d * scale, alpha_only);
}

// Coverage of an alpha-tested material (alpha factor x base colour texture alpha, the texture read
// at its finest level: the same test for every ray, in both frames) against its cutoff.
bool alpha_keeps(GpuMaterialTextures m, vec4 uv) {
  if (m.alpha_mode != ALPHA_MASK) return true;
  float a = m.alpha;
  if (m.base_color.texture >= 0) a *= sample_texture_ref(m.base_color, uv, vec2(0.0), 0.0, true).a;
  return a >= m.alpha_cutoff;
}

#endif
