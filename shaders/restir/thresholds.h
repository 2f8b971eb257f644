// Every robustness threshold of the resampling library, in one place (docs/ARCHITECTURE.md, Robustness).
#ifndef STRATA_RESTIR_THRESHOLDS_H
#define STRATA_RESTIR_THRESHOLDS_H
#include "include/lang.h"

STRATA_NAMESPACE_BEGIN

// Reconnection is refused at vertices smoother than this GGX alpha (near-specular lobes make the
// reconnection Jacobian and the BSDF ratio explode; Lin et al. 2022 use a roughness threshold too).
// 0.03 (roughness 0.17) was measured against 0.2 and 0.05 (docs/BENCHMARKS.md, "The history search
// and glossy reconnection vertices"): glossy dielectrics and metals down to roughness 0.2 reconnect,
// and their pixels stop replaying whole paths that rarely survive the shift (chess RelMSE -14%,
// carousel -9%); mirror-like lobes (stiff's alpha 4e-4) still do not.
CONST_DEF float RECONNECT_MIN_ALPHA = 0.03f;
// Reconnection edges shorter than this fraction of the distance to the camera are refused: the
// 1/d^2 factor of the Jacobian is unstable for near-coincident vertices.
CONST_DEF float RECONNECT_MIN_EDGE_RELATIVE = 1e-2f;
// A reconnection's visibility ray that is blocked by x_k's own mesh part within this fraction of
// the edge's length counts as unblocked (restir/path_space.glsl, reconnection_visible): traversal
// rounding, not an occluder. The bias it allows (an occluder of the same mesh part closer than 1% of
// the edge to x_k) is far below the failures it removes.
CONST_DEF float RECONNECT_SELF_TOLERANCE = 1e-2f;
// |cos| below this at a reconnection or primary vertex is grazing: the Jacobian (RS-main Eq. 15,
// Lin 2022 reconnection Jacobian) is singular there, so the shift fails.
CONST_DEF float SHIFT_MIN_COS = 1e-3f;
// Jacobians outside [1/J_MAX, J_MAX] fail the shift instead of producing a huge weight.
CONST_DEF float SHIFT_MAX_JACOBIAN = 1e4f;
// Spatial neighbours are refused when their pixel-centre surface turns away from this pixel's by
// more than 25 degrees or lies more than 10% further or nearer along the centre ray: the geometric
// similarity test of Bitterli et al. 2020 (ReSTIR DI, section 6.1), taken by Lin et al. 2022.
CONST_DEF float SPATIAL_MIN_NORMAL_COS = 0.906f;  // cos 25 degrees
CONST_DEF float SPATIAL_MAX_DEPTH_RELATIVE = 0.1f;

STRATA_NAMESPACE_END
#endif
