// Reservoir splatting's per-splat record (restir-splat, RS-supp 3.1): shared by the projection,
// insertion and resampling passes.
#ifndef STRATA_SPLAT_DATA_H
#define STRATA_SPLAT_DATA_H
#include "include/lang.h"
#include "restir/reservoir.h"

STRATA_NAMESPACE_BEGIN

CONST_DEF uint SPLAT_NONE = 0xFFFFFFFFu;  // BINDING_SPLAT_TARGET of a reservoir that did not land

// The previous pixel i's reservoir X_i splatted forward as Y_i = T(X_i) (RS-main 4.1.1): the packed
// reservoir holds Y_i's sample with X_i's W (ucw), capped confidence c_i and p-hat_prev(X_i); the
// second word holds f(Y_i) and |T'(X_i)|. 112 bytes.
struct SplatRecord {
  PackedReservoir reservoir;
  vec4 f_jacobian;
};

STRATA_NAMESPACE_END
#endif
