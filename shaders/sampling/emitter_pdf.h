// The density with which next-event estimation picks a point on an emitter, for the MIS weights
// of every strategy that hits an emitter by other means (pt's BSDF sampling, ReSTIR's candidates
// and shifts in either frame). One definition for the host's alias table (render/emitters.cpp:
// triangles in proportion to their power, luminance * area * sides) and the passes.
#ifndef STRATA_EMITTER_PDF_H
#define STRATA_EMITTER_PDF_H
#include "include/lang.h"
#include "material/bsdf.h"

STRATA_NAMESPACE_BEGIN

// Solid-angle density at a shading point `distance` away, under |cos_light| at the emitter: the
// emitter triangle is chosen with probability (1 - env_select) power / total_power, then a point
// on it uniformly by area. total_power and env_select are those of the frame whose light sampler
// is meant; 0 where the density is undefined.
INLINE float emitter_solid_angle_pdf(float total_power, float env_select, vec3 emission, float area, bool double_sided,
                                     float distance, float cos_light) {
  float c = abs(cos_light);
  if (!(total_power > 0.0f) || !(area > 0.0f) || !(c > 0.0f)) return 0.0f;
  float pmf = (1.0f - env_select) * luminance(emission) * area * (double_sided ? 2.0f : 1.0f) / total_power;
  return pmf / area * distance * distance / c;
}

STRATA_NAMESPACE_END
#endif
