// Counter-based random numbers: a PCG hash seeds a PCG32 stream per (pixel, sample, frame, seed).
#ifndef STRATA_RNG_H
#define STRATA_RNG_H
#include "include/lang.h"

STRATA_NAMESPACE_BEGIN

// PCG-RXS-M-XS 32-bit hash (Jarzynski & Olano 2020, "Hash Functions for GPU Rendering").
INLINE uint pcg_hash(uint v) {
  uint state = v * 747796405u + 2891336453u;
  uint word = ((state >> ((state >> 28u) + 4u)) ^ state) * 277803737u;
  return (word >> 22u) ^ word;
}

struct Rng {
  uint state;
};

INLINE Rng rng_init(uint pixel, uint sample_index, uint frame, uint seed) {
  Rng r;
  r.state = pcg_hash(pixel ^ pcg_hash(sample_index ^ pcg_hash(frame ^ pcg_hash(seed))));
  return r;
}

INLINE uint rng_next_uint(INOUT(Rng) r) {
  r.state = r.state * 747796405u + 2891336453u;
  uint word = ((r.state >> ((r.state >> 28u) + 4u)) ^ r.state) * 277803737u;
  return (word >> 22u) ^ word;
}

// Uniform in [0, 1): the top 24 bits, so 1.0 is never returned.
INLINE float rng_next_float(INOUT(Rng) r) {
  return float(rng_next_uint(r) >> 8u) * (1.0f / 16777216.0f);
}

INLINE vec2 rng_next_float2(INOUT(Rng) r) {
  float a = rng_next_float(r);
  float b = rng_next_float(r);
  return vec2(a, b);
}

// Random numbers addressed by dimension: the hybrid shift replays a path by asking for the same
// dimensions of the same key (Lin et al. 2022, random replay), whatever branches were taken before.
INLINE uint rng_key(uint pixel, uint sample_index, uint frame, uint seed) {
  return pcg_hash(pixel ^ pcg_hash(sample_index ^ pcg_hash(frame ^ pcg_hash(seed + 0x6A09E667u))));
}

INLINE float rng_dim(uint key, uint dim) {
  return float(pcg_hash(key ^ pcg_hash(dim + 0x9E3779B9u)) >> 8u) * (1.0f / 16777216.0f);
}

STRATA_NAMESPACE_END
#endif
