// Texture lookups of the scene bridge (include/scene_bridge.glsl includes this file in the passes'
// textured variants, compiled with STRATA_TEXTURES; nothing else includes it). Texels are linear
// RGBA16 (sRGB images decoded on the host, before any filtering) in one storage buffer
// (include/texture_data.h) and are filtered here: wrap modes are applied per texel, and the mip
// level follows from a footprint width in UV units (the scene bridge's footprint rule: material_at).
#ifndef STRATA_TEXTURES_GLSL
#define STRATA_TEXTURES_GLSL

#include "include/bindings.h"
#include "include/texture_data.h"

layout(set = 0, binding = BINDING_MATERIAL_TEXTURES, std430) readonly buffer MaterialTextures { GpuMaterialTextures b_material_textures[]; };
layout(set = 0, binding = BINDING_TEXTURES, std430) readonly buffer Textures { GpuTexture b_textures[]; };
layout(set = 0, binding = BINDING_TEXTURE_LEVELS, std430) readonly buffer TextureLevels { GpuMipLevel b_texture_levels[]; };
layout(set = 0, binding = BINDING_TEXELS, std430) readonly buffer Texels { uvec2 b_texels[]; };
layout(set = 0, binding = BINDING_VERTEX_EXTRAS, std430) readonly buffer VertexExtras { GpuVertexExtra b_vertex_extras[]; };
// Per triangle (its first index / 3): the emission light sampling selects it by (render/scene_textures.h,
// triangle_light_emission), read for materials with an emissive texture only.
layout(set = 0, binding = BINDING_LIGHT_EMISSION, std430) readonly buffer LightEmission { vec4 b_light_emission[]; };

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

// A texel: linear RGBA (render/scene_textures.h decodes sRGB images when it uploads them, so that a
// texel read is one load: a pow per channel and texel made a textured frame 1.2-1.3x an untextured one).
vec4 texel_at(GpuMipLevel l, uint x, uint y) {
  uvec2 w = b_texels[l.offset + y * l.width + x];
  return vec4(unpackUnorm2x16(w.x), unpackUnorm2x16(w.y));
}

// Texture `t` at uv with a footprint `width_uv` wide in UV units (0: the finest level). The level
// of detail is log2 of the footprint in level-0 texels (Akenine-Moeller et al. 2019, "Texture Level
// of Detail Strategies for Real-Time Ray Tracing", Eq. 34 with the width already projected); at
// or below 0 the magnification filter reads level 0, above it the minification filter reads the
// level(s) the sampler's mipmap mode picks: one level (nearest, or none), or two weighted by the
// fraction of the level of detail (linear). Each level is read nearest or bilinear (texel centres
// at half-integers, as Vulkan samples).
//
// The levels and the texels of a level are loops with one texel read in them, not one read per
// texel and level written out: every call site of a lookup is inlined, and the passes' textured
// variants hold dozens (material_at at each kind of vertex, the alpha test in every ray query),
// whose compile time on lavapipe grows with the code.
vec4 sample_texture(uint t, vec2 uv, float width_uv) {
  GpuTexture tex = b_textures[t];
  uint sampling = tex.sampling;
  uint wrap_u = (sampling >> TEXTURE_WRAP_U_SHIFT) & 3u;
  uint wrap_v = (sampling >> TEXTURE_WRAP_V_SHIFT) & 3u;
  // A non-finite UV reads the first texel; a finite one is folded into one period of every wrap mode
  // (repeat and mirror repeat over 2, clamp just outside [0, 1]) so that texel indices stay small.
  if (any(isnan(uv)) || any(isinf(uv))) uv = vec2(0.0);
  vec2 folded = uv - 2.0 * floor(uv * 0.5);
  vec2 clamped = clamp(uv, vec2(-1.0), vec2(2.0));
  uv.x = wrap_u == TEXTURE_WRAP_CLAMP ? clamped.x : folded.x;
  uv.y = wrap_v == TEXTURE_WRAP_CLAMP ? clamped.y : folded.y;
  GpuMipLevel base = b_texture_levels[tex.first_level];
  float texels = width_uv * sqrt(float(base.width) * float(base.height));
  float lambda = texels > 0.0 ? log2(texels) : -1.0;
  uint first = tex.first_level;
  uint levels = 1u;
  float upper = 0.0;  // the weight of the second level
  bool linear = (sampling & TEXTURE_MAG_LINEAR) != 0u;
  if (lambda > 0.0) {
    linear = (sampling & TEXTURE_MIN_LINEAR) != 0u;
    uint mip = (sampling >> TEXTURE_MIP_SHIFT) & 3u;
    lambda = min(lambda, float(tex.level_count - 1u));
    float lo = floor(lambda);
    if (mip == TEXTURE_MIP_NEAREST) first += uint(floor(lambda + 0.5));
    if (mip == TEXTURE_MIP_LINEAR) {
      first += uint(lo);
      upper = lambda - lo;
      levels = upper > 0.0 ? 2u : 1u;
    }
  }
  uint corners = linear ? 4u : 1u;
  vec4 sum = vec4(0.0);
  for (uint k = 0u; k < levels; ++k) {
    GpuMipLevel l = b_texture_levels[first + k];
    ivec2 n = ivec2(l.width, l.height);
    vec2 p = uv * vec2(n) - (linear ? 0.5 : 0.0);
    vec2 f = floor(p);
    ivec2 i = ivec2(f);
    f = p - f;
    float level_weight = k == 0u ? 1.0 - upper : upper;
    for (uint c = 0u; c < corners; ++c) {
      uvec2 d = uvec2(c & 1u, c >> 1u);  // bilinear: (0, 0), (1, 0), (0, 1), (1, 1); nearest: (0, 0)
      vec2 w = mix(1.0 - f, f, vec2(d));
      float weight = level_weight * (linear ? w.x * w.y : 1.0);
      uint x = uint(wrap_texel(i.x + int(d.x), n.x, wrap_u));
      uint y = uint(wrap_texel(i.y + int(d.y), n.y, wrap_v));
      sum += weight * texel_at(l, x, y);
    }
  }
  return sum;
}

// A material's texture at a surface whose texCoord sets are `uv` (xy set 0, zw set 1) with
// `density` UV units per render-space unit (x set 0, y set 1), for a footprint `width` wide in
// render space. KHR_texture_transform moves the UV and scales the footprint with it.
vec4 sample_texture_ref(GpuTextureRef r, vec4 uv, vec2 density, float width) {
  vec2 t = r.tex_coord == 1u ? uv.zw : uv.xy;
  float d = r.tex_coord == 1u ? density.y : density.x;
  vec2 tuv = vec2(dot(r.row0.xyz, vec3(t, 1.0)), dot(r.row1.xyz, vec3(t, 1.0)));
  float scale = sqrt(abs(r.row0.x * r.row1.y - r.row0.y * r.row1.x));
  return sample_texture(uint(r.texture), tuv, width * d * scale);
}

// Coverage of an alpha-tested material (alpha factor x base colour texture alpha, the texture read
// at its finest level: the same test for every ray, in both frames) against its cutoff.
bool alpha_keeps(uint material, vec4 uv) {
  if (b_material_textures[material].alpha_mode != ALPHA_MASK) return true;
  float a = b_material_textures[material].alpha;
  if ((b_material_textures[material].textures & (1u << MATERIAL_TEXTURE_BASE_COLOR)) != 0u)
    a *= sample_texture_ref(b_material_textures[material].slots[MATERIAL_TEXTURE_BASE_COLOR], uv, vec2(0.0), 0.0).a;
  return a >= b_material_textures[material].alpha_cutoff;
}

#endif
