// Every random stream of the ReSTIR passes, named once. A stream is the second argument of
// rng_init / rng_key (sampling/rng.h): with the pixel (or domain), the frame index and the session
// seed it keys an independent sequence, so two uses must never share a name. The salts are
// arbitrary distinct constants, far above any path index; changing one changes every frame.
#ifndef STRATA_RESTIR_RNG_STREAMS_H
#define STRATA_RESTIR_RNG_STREAMS_H
#include "include/lang.h"
#include "restir/restir_limits.h"

STRATA_NAMESPACE_BEGIN

// rng_key streams per pixel (or deep domain): path p of the initial estimator is stream p
// (0 <= p < RESTIR_MAX_INITIAL_CANDIDATES; the primary pass's camera sample is path 0's), then the
// stratified camera samples of what the camera sees directly and of the albedo control variate.
CONST_DEF uint RNG_STREAM_PATH_FIRST = 0u;
CONST_DEF uint RNG_STREAM_DIRECT_STRATA = RESTIR_MAX_INITIAL_CANDIDATES;          // G x G, G <= RESTIR_MAX_DIRECT_STRATA
CONST_DEF uint RNG_STREAM_ALBEDO_STRATA = RESTIR_MAX_INITIAL_CANDIDATES + 64u;

// rng_init salts of the resampling passes' selection streams (the u of gris_stream) and draws.
CONST_DEF uint RNG_SALT_INITIAL_SELECT = 0x51EC7u;   // restir_initial.comp: selection among the candidates
CONST_DEF uint RNG_SALT_TEMPORAL_SELECT = 0x7E3A0u;  // restir_temporal.comp: canonical or history
CONST_DEF uint RNG_SALT_SPATIAL = 0x5A71A1u;         // restir_spatial.comp: neighbour draws, then the selection
CONST_DEF uint RNG_SALT_SPATIAL_PAIRS = 0x9A125u;    // restir/spatial_pairs.glsl: the frame's pair offsets (pixel 0)
CONST_DEF uint RNG_SALT_SPLAT_SELECT = 0x5B1A7u;     // restir_splat_resample.comp: selection among the splats

STRATA_NAMESPACE_END
#endif
