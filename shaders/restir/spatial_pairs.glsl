// Paired spatial neighbours (docs/ARCHITECTURE.md, "Paired neighbours"). Pairwise MIS (restir/gris.h)
// needs two shifts per neighbour j of pixel i: y_j into i, and the canonical y_i into j (for the
// canonical sample's weight, RS-main Eq. 7). When i takes j and j takes i, each of those shifts is
// the other pixel's first one. So every frame draws k_pair_offsets offsets o_m (uniform in the disk
// of spatial_radius, whole pixels, not 0, none another's or its negative) and every pixel i takes
// i + o_m and i - o_m as its first neighbours, where the two pixel-centre surfaces are alike both
// ways (similar_pair: the relation is symmetric, so j takes i exactly when i takes j).
// restir_spatial_pairs.comp shifts these neighbours' samples into i once and stores them
// (PairShift); restir_spatial.comp reads its own records as the neighbours' forward shifts and the
// neighbours' records of i as the reverse ones: one shift per pixel and neighbour instead of two.
// The offsets are frame constants and the test reads geometry only, so the domains still do not
// depend on the samples and the MIS weights stay unbiased.
// Needs restir/restir_pass.glsl, restir/path_space.glsl and restir/centre_surface.glsl.
#ifndef STRATA_SPATIAL_PAIRS_GLSL
#define STRATA_SPATIAL_PAIRS_GLSL

#include "restir/spatial_pair_data.h"
#include "restir/rng_streams.h"
#include "sampling/rng.h"
#include "sampling/warp.h"

layout(set = 0, binding = BINDING_SPATIAL_PAIRS, std430) buffer SpatialPairs { PairShift b_pairs[]; };
// The number of pair offsets (0: no pairs; SPATIAL_MAX_PAIR_OFFSETS at most); 2 slots each.
layout(constant_id = SPEC_SPATIAL_PAIRS) const uint k_pair_offsets = 0u;

uint pair_slots() { return 2u * min(k_pair_offsets, SPATIAL_MAX_PAIR_OFFSETS); }

// The frame's pair offsets o_0 .. o_{k_pair_offsets - 1}. A radius that holds too few pixels for
// distinct offsets falls back to unit steps along x (each distinct as long as the image is wider).
void spatial_pair_offsets(out ivec2 o[SPATIAL_MAX_PAIR_OFFSETS]) {
  Rng rng = frame_rng(0u, RNG_SALT_SPATIAL_PAIRS);
  for (uint m = 0u; m < SPATIAL_MAX_PAIR_OFFSETS; ++m) {
    o[m] = ivec2(int(m) + 1, 0);
    if (m >= k_pair_offsets) continue;
    for (uint t = 0u; t < 32u; ++t) {
      ivec2 d = ivec2(round(sample_concentric_disk(rng_next_float2(rng)) * restir_spatial_radius()));
      bool fresh = d != ivec2(0);
      for (uint l = 0u; l < m; ++l) fresh = fresh && d != o[l] && d != -o[l];
      if (fresh) {
        o[m] = d;
        break;
      }
    }
  }
}

// Slot 2m is the neighbour at +o_m, slot 2m + 1 at -o_m; slot s ^ 1 is its opposite.
ivec2 pair_direction(ivec2 o[SPATIAL_MAX_PAIR_OFFSETS], uint slot) {
  ivec2 d = o[min(slot / 2u, SPATIAL_MAX_PAIR_OFFSETS - 1u)];
  return (slot & 1u) == 0u ? d : -d;
}

// The filter both ways (similar_surface measures the depth against the first argument's).
bool similar_pair(CentreSurface a, CentreSurface b) { return similar_surface(a, b) && similar_surface(b, a); }


uint pair_record(uvec2 pixel, uint slot) { return pixel_index(pixel) * pair_slots() + slot; }

void store_pair(uvec2 pixel, uint slot, ShiftResult s) {
  PairShift p;
  bool ok = s.reason == SHIFT_OK;
  p.x1 = pack_surface(s.x1);
  p.f_jacobian = ok ? vec4(s.f, s.jacobian) : vec4(0.0);
  p.meta = uvec4(floatBitsToUint(s.density), s.x1.lod, 0u, 0u);
  b_pairs[pair_record(pixel, slot)] = p;
}

// The stored shift of slot `slot` of `pixel`, as shift_path returned it; `camera` is the offset
// path's camera sample (the domain's with a fixed primary vertex, else the sample's own).
ShiftResult load_pair(uvec2 pixel, uint slot, CameraSample camera) {
  PairShift p = b_pairs[pair_record(pixel, slot)];
  ShiftResult r = shift_none(p.f_jacobian.w > 0.0 ? SHIFT_OK : SHIFT_FAIL_ZERO);
  r.f = p.f_jacobian.rgb;
  r.jacobian = p.f_jacobian.w;
  r.density = uintBitsToFloat(p.meta.x);
  r.x1 = unpack_surface(p.x1, p.meta.y);
  r.camera = camera;
  return r;
}

#endif
