// Every robustness threshold of the resampling library, in one place (docs/ARCHITECTURE.md, Robustness).
#ifndef STRATA_RESTIR_THRESHOLDS_H
#define STRATA_RESTIR_THRESHOLDS_H
#include "include/lang.h"

STRATA_NAMESPACE_BEGIN

// Reconnection is refused at vertices smoother than this GGX alpha (near-specular lobes make the
// reconnection Jacobian and the BSDF ratio explode; Lin et al. 2022 use a roughness threshold too).
CONST_DEF float RECONNECT_MIN_ALPHA = 0.2f;
// Reconnection edges shorter than this fraction of the distance to the camera are refused: the
// 1/d^2 factor of the Jacobian is unstable for near-coincident vertices.
CONST_DEF float RECONNECT_MIN_EDGE_RELATIVE = 1e-2f;
// |cos| below this at a reconnection or primary vertex is grazing: the Jacobian (RS-main Eq. 15,
// Lin 2022 reconnection Jacobian) is singular there, so the shift fails.
CONST_DEF float SHIFT_MIN_COS = 1e-3f;
// Jacobians outside [1/J_MAX, J_MAX] fail the shift instead of producing a huge weight.
CONST_DEF float SHIFT_MAX_JACOBIAN = 1e4f;
// Default confidence cap c_cap (docs/ARCHITECTURE.md, Methods).
CONST_DEF float CONFIDENCE_CAP_DEFAULT = 20.0f;

STRATA_NAMESPACE_END
#endif
