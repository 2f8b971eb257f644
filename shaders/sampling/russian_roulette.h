// Russian roulette of the path tracer and of ReSTIR's candidate paths: one rule for both.
#ifndef STRATA_RUSSIAN_ROULETTE_H
#define STRATA_RUSSIAN_ROULETTE_H
#include "include/lang.h"

STRATA_NAMESPACE_BEGIN

CONST_DEF float RR_START_DEPTH = 3.0f;    // vertices before a path may be terminated
CONST_DEF float RR_MAX_SURVIVAL = 0.95f;  // never certain survival: long paths always end

// Survival probability of a path with throughput `beta` (its largest channel, capped).
INLINE float rr_survival(vec3 beta) { return min(max(beta.r, max(beta.g, beta.b)), RR_MAX_SURVIVAL); }

STRATA_NAMESPACE_END
#endif
