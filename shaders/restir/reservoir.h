// Path samples and reservoirs (docs/ARCHITECTURE.md, State), and their packed form in device memory.
//
// A path sample is an area reservoir's sample (Zhang et al. 2024; RS-main 3.5): the primary hit
// x1 is stored as the surface point itself (instance, primitive, triangle, barycentrics and LoD
// level: object space, so it moves with its object and can be splatted exactly, RS-main 4.1.1),
// as is the reconnection vertex x_k, with the direction leaving x_k (in x_k's surface frame, so that
// it turns with its object) and the radiance arriving along it so that the BSDF at x_k can be
// re-evaluated for a new predecessor (reconnection shift).
// Positions are never stored in fp16: barycentrics are f32; radiance is f32 because emitters may
// exceed fp16's 65504 (the `stiff` scene has 1e6); the confidence weight is 16-bit; the shutter time
// is f32, as it is replayed exactly.
//
// Shift bookkeeping (Lin et al. 2022 hybrid shift, as strata defines it in restir/path_space.glsl):
// the subpixel jitter and lens sample are replayed exactly (identity shift in those dimensions);
// vertices x_2 .. x_{k-1} are replayed from `seed`; x_k and everything after it is kept. `density`
// is the path's replay density: the product of the BSDF densities of the replayed directions over
// (cos theta_k / |x_k - x_{k-1}|^2) * area(x_k's triangle) when the path reconnects, so that every
// shift's Jacobian is density(base) / density(offset). `light_pdf_end` is the NEE density of the
// last vertex as seen from x_{n-1}, which the MIS weight of the path's technique needs when
// x_{n-1} = x_k is re-entered from a new direction. `suffix_density` and `light_index` serve the
// suffix replay (restir/suffix_replay.glsl): the density of the suffix's sampled decisions after
// x_k, and which light candidate of x_{n-1} chose an NEE end.
#ifndef STRATA_RESTIR_RESERVOIR_H
#define STRATA_RESTIR_RESERVOIR_H
#include "include/lang.h"

STRATA_NAMESPACE_BEGIN

// Field widths of the packed surface point.
CONST_DEF uint SURFACE_INSTANCE_BITS = 20u;  // instances 0 .. 2^20 - 2 (all ones marks "no surface")
CONST_DEF uint SURFACE_GEOMETRY_BITS = 12u;  // up to 4,096 primitives per mesh
CONST_DEF uint SURFACE_LOD_BITS = 4u;        // up to 16 LoD levels
CONST_DEF uint SURFACE_NONE = 0xFFFFFFFFu;   // instance word of "no surface" (escaped, or unused)

// Path sample flags.
CONST_DEF uint SAMPLE_VALID = 1u;         // the reservoir holds a sample
CONST_DEF uint SAMPLE_EMITTER_HIT = 2u;   // the path ends by hitting an emitter (not by NEE)
CONST_DEF uint SAMPLE_ESCAPED = 4u;       // the path ends in the environment
CONST_DEF uint SAMPLE_NEE = 8u;           // the last vertex was chosen by next-event estimation
CONST_DEF uint SAMPLE_XK_IS_LAST = 16u;   // x_k is the path's last vertex (k == segments)
CONST_DEF uint SAMPLE_PUNCTUAL = 32u;     // the path ends at a punctual light chosen by NEE; when it is x_k
                                          // (k == segments) x_k is no surface and its `triangle` is the light's index

struct SurfacePoint {
  uint instance;   // SURFACE_NONE: no surface
  uint geometry;   // primitive of the instance's mesh at `lod`
  uint triangle;
  vec2 bary;       // barycentrics of vertices 1 and 2 (Vulkan's convention)
  uint lod;
};

struct PathSample {
  SurfacePoint x1;        // primary hit
  SurfacePoint xk;        // reconnection vertex
  vec3 xk_direction;      // k < n: unit direction leaving x_k towards x_{k+1}, in x_k's surface frame
                          // (surface_to_local, path_vertex.glsl); k = n: the world direction from
                          // x_{k-1} (the escape direction if escaped)
  vec3 xk_radiance;       // radiance arriving at x_k along -xk_direction (emission of x_k excluded)
  uint k;                 // index of x_k (x0 is the camera); 0 = not reconnectable
  uint segments;          // number of path segments (path length)
  uint flags;             // SAMPLE_*
  uint seed;              // random-replay seed of the hybrid shift (Lin et al. 2022)
  vec2 lens;              // thin-lens sample in [0,1)^2 (stored as unorm16: generated already quantized)
  float time;             // time within the shutter in [0,1)
  vec2 jitter;            // subpixel position in [0,1)^2 (box filter), f32
  float density;          // replay density (see above)
  float light_pdf_end;    // NEE solid-angle density of the last vertex from x_{n-1} (0: not NEE-able)
  float suffix_density;   // product of the densities of the directions sampled at x_{k+1} .. x_{n-1}
                          // (BSDF, or the light sample of an NEE end); 1 when nothing after x_k is sampled
  uint light_index;       // NEE end: the light candidate of x_{n-1} that chose x_n (its random numbers)
};

struct Reservoir {
  PathSample y;
  float ucw;         // unbiased contribution weight W_Y (RS-main Eq. 5)
  float confidence;  // c (RS-main 3.4)
  float p_hat;       // target function value of y in its own pixel, cached
};

// 96 bytes: six 16-byte words (budget: <= 96).
struct PackedReservoir {
  uvec4 x1;          // instance|geometry, triangle, bary.x, bary.y
  uvec4 xk;          // instance|geometry, triangle, bary.x, bary.y
  uvec4 radiance;    // xk_radiance rgb (f32), packed xk_direction (octahedral snorm16x2)
  uvec4 weights;     // ucw (f32), p_hat (f32), seed, half(confidence) | light_index << 16
  uvec4 meta;        // k | length << 8 | flags << 16 | lod1 << 24 | lodk << 28, lens (unorm16x2), time (f32), suffix_density (f32)
  uvec4 shift;       // jitter.x, jitter.y, density, light_pdf_end (f32)
};

INLINE SurfacePoint surface_none() {
  SurfacePoint s;
  s.instance = SURFACE_NONE;
  s.geometry = 0u;
  s.triangle = 0u;
  s.bary = vec2(0.0f);
  s.lod = 0u;
  return s;
}

// Octahedral map of a unit vector to [-1,1]^2 (Cigolle et al. 2014).
INLINE vec2 octahedral_encode(vec3 n) {
  float l1 = abs(n.x) + abs(n.y) + abs(n.z);
  vec2 p = vec2(n.x, n.y) * (1.0f / max(l1, 1e-20f));
  if (n.z < 0.0f) {
    vec2 s = vec2(p.x >= 0.0f ? 1.0f : -1.0f, p.y >= 0.0f ? 1.0f : -1.0f);
    p = (vec2(1.0f) - abs(vec2(p.y, p.x))) * s;
  }
  return p;
}

INLINE vec3 octahedral_decode(vec2 p) {
  vec3 n = vec3(p.x, p.y, 1.0f - abs(p.x) - abs(p.y));
  float t = max(-n.z, 0.0f);
  n.x += n.x >= 0.0f ? -t : t;
  n.y += n.y >= 0.0f ? -t : t;
  return normalize(n);
}

INLINE uvec4 pack_surface(SurfacePoint s) {
  uint id = s.instance == SURFACE_NONE ? SURFACE_NONE : (s.instance | (s.geometry << SURFACE_INSTANCE_BITS));
  return uvec4(id, s.triangle, floatBitsToUint(s.bary.x), floatBitsToUint(s.bary.y));
}

INLINE SurfacePoint unpack_surface(uvec4 w, uint lod) {
  SurfacePoint s;
  if (w.x == SURFACE_NONE) {
    s = surface_none();
    s.triangle = w.y;  // a punctual light's index (SAMPLE_PUNCTUAL), else 0
    return s;
  }
  s.instance = w.x & ((1u << SURFACE_INSTANCE_BITS) - 1u);
  s.geometry = w.x >> SURFACE_INSTANCE_BITS;
  s.triangle = w.y;
  s.bary = vec2(uintBitsToFloat(w.z), uintBitsToFloat(w.w));
  s.lod = lod;
  return s;
}

INLINE PackedReservoir pack_reservoir(Reservoir r) {
  PackedReservoir p;
  p.x1 = pack_surface(r.y.x1);
  p.xk = pack_surface(r.y.xk);
  p.radiance = uvec4(floatBitsToUint(r.y.xk_radiance.x), floatBitsToUint(r.y.xk_radiance.y),
                     floatBitsToUint(r.y.xk_radiance.z), packSnorm2x16(octahedral_encode(r.y.xk_direction)));
  p.weights = uvec4(floatBitsToUint(r.ucw), floatBitsToUint(r.p_hat), r.y.seed,
                    (packHalf2x16(vec2(r.confidence, 0.0f)) & 0xFFFFu) | ((r.y.light_index & 0xFFFFu) << 16u));
  uint meta = (r.y.k & 0xFFu) | ((r.y.segments & 0xFFu) << 8u) | ((r.y.flags & 0xFFu) << 16u) | ((r.y.x1.lod & 0xFu) << 24u) |
              ((r.y.xk.lod & 0xFu) << 28u);
  p.meta = uvec4(meta, packUnorm2x16(r.y.lens), floatBitsToUint(r.y.time), floatBitsToUint(r.y.suffix_density));
  p.shift = uvec4(floatBitsToUint(r.y.jitter.x), floatBitsToUint(r.y.jitter.y), floatBitsToUint(r.y.density),
                  floatBitsToUint(r.y.light_pdf_end));
  return p;
}

INLINE Reservoir unpack_reservoir(PackedReservoir p) {
  Reservoir r;
  uint meta = p.meta.x;
  r.y.x1 = unpack_surface(p.x1, (meta >> 24u) & 0xFu);
  r.y.xk = unpack_surface(p.xk, (meta >> 28u) & 0xFu);
  r.y.xk_radiance = vec3(uintBitsToFloat(p.radiance.x), uintBitsToFloat(p.radiance.y), uintBitsToFloat(p.radiance.z));
  r.y.xk_direction = octahedral_decode(unpackSnorm2x16(p.radiance.w));
  r.ucw = uintBitsToFloat(p.weights.x);
  r.p_hat = uintBitsToFloat(p.weights.y);
  r.y.seed = p.weights.z;
  r.confidence = unpackHalf2x16(p.weights.w & 0xFFFFu).x;
  r.y.light_index = p.weights.w >> 16u;
  r.y.time = uintBitsToFloat(p.meta.z);
  r.y.k = meta & 0xFFu;
  r.y.segments = (meta >> 8u) & 0xFFu;
  r.y.flags = (meta >> 16u) & 0xFFu;
  r.y.lens = unpackUnorm2x16(p.meta.y);
  r.y.jitter = vec2(uintBitsToFloat(p.shift.x), uintBitsToFloat(p.shift.y));
  r.y.density = uintBitsToFloat(p.shift.z);
  r.y.light_pdf_end = uintBitsToFloat(p.shift.w);
  r.y.suffix_density = uintBitsToFloat(p.meta.w);
  return r;
}

STRATA_NAMESPACE_END

#ifdef __cplusplus
static_assert(sizeof(strata::gpu::PackedReservoir) == 96, "docs/ARCHITECTURE.md, State: <= 96 bytes per reservoir");
#endif
#endif
