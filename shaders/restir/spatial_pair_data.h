// The spatial stage's paired neighbours (restir_spatial_pairs.comp, docs/ARCHITECTURE.md "Paired
// neighbours"): per pixel and pair slot (2m: the neighbour at +o_m, 2m + 1: at -o_m) that
// neighbour's reservoir sample shifted into this pixel's domain, which the neighbour's own
// resampling reads as the reverse shift of its canonical sample. 48 bytes.
#ifndef STRATA_SPATIAL_PAIR_DATA_H
#define STRATA_SPATIAL_PAIR_DATA_H
#include "include/lang.h"

STRATA_NAMESPACE_BEGIN

CONST_DEF uint SPATIAL_MAX_PAIR_OFFSETS = 4u;  // o_0 .. o_3: up to 8 paired neighbours

struct PairShift {
  uvec4 x1;          // the offset path's primary hit (pack_surface)
  vec4 f_jacobian;   // f(T(y)) rgb, |dT/dy| (0: no shift: no pair, no sample, or the shift failed)
  uvec4 meta;        // replay density of T(y) (f32 bits), x1's LoD, 0, 0
};

// The spatial pass's push constant (restir_spatial.comp): list = 1 in the indirect dispatch that
// runs the pixels the image dispatch listed (SPEC_SPATIAL_COMPACT), 0 in the image dispatch. One
// pipeline serves both.
struct SpatialDispatch {
  uint list;
};

STRATA_NAMESPACE_END
#endif
