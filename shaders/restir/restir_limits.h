// Ranges of the ReSTIR options, defined once for the host (validation of sessions and of
// `stratad render`) and the passes (fixed-size arrays).
#ifndef STRATA_RESTIR_LIMITS_H
#define STRATA_RESTIR_LIMITS_H
#include "include/lang.h"

STRATA_NAMESPACE_BEGIN

CONST_DEF uint RESTIR_MAX_SPATIAL_NEIGHBORS = 8u;   // restir_spatial.comp keeps them in an array
CONST_DEF uint RESTIR_MAX_INITIAL_CANDIDATES = 64u;
CONST_DEF uint RESTIR_MAX_LIGHT_CANDIDATES = 32u;
CONST_DEF uint RESTIR_MAX_SPLATS_PER_FRAME = 64u;   // K time partitions (RS-main Eq. 19)
CONST_DEF uint RESTIR_MAX_DIRECT_STRATA = 8u;       // G x G camera samples for what the camera sees directly
CONST_DEF float RESTIR_MIN_CONFIDENCE_CAP = 1.0f;
CONST_DEF float RESTIR_MAX_CONFIDENCE_CAP = 1000.0f;
CONST_DEF float RESTIR_MIN_SPATIAL_RADIUS = 1.0f;   // pixels
CONST_DEF float RESTIR_MAX_SPATIAL_RADIUS = 256.0f;
// Candidates drawn per neighbour slot until one passes the surface filter (restir_spatial.comp).
CONST_DEF uint RESTIR_SPATIAL_TRIES = 4u;
// Previous pixels tried, nearest to the backprojected position first, until one's centre surface
// passes the history filter (restir_temporal.comp): the pixel itself and the rest of its 3 x 3.
CONST_DEF uint RESTIR_TEMPORAL_TRIES = 9u;
// restir-multilayer: the hole filling radius (ML 4.3 uses 3; domain_fill.comp reads (2r+1)^2 marks).
CONST_DEF uint RESTIR_MAX_HOLE_FILL_RADIUS = 8u;
// restir-multilayer: the silhouette band (domain_fill.comp reads up to (2r+1)^2 front-layer flags
// per pixel with an active deep domain).
CONST_DEF uint RESTIR_MAX_SILHOUETTE_BAND = 32u;
CONST_DEF uint RESTIR_MAX_REVEAL_LOOKAHEAD = 16u;  // frames

STRATA_NAMESPACE_END
#endif
