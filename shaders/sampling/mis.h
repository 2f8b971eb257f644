// Multiple importance sampling weights (Veach 1997, ch. 9).
#ifndef STRATA_MIS_H
#define STRATA_MIS_H
#include "include/lang.h"

STRATA_NAMESPACE_BEGIN

// Power heuristic with beta = 2 for one sample from each of two strategies.
INLINE float mis_power(float pdf_this, float pdf_other) {
  float a = pdf_this * pdf_this;
  float b = pdf_other * pdf_other;
  float s = a + b;
  if (!(s > 0.0f) || isinf(s)) return pdf_this >= pdf_other ? 1.0f : 0.0f;
  return a / s;
}

STRATA_NAMESPACE_END
#endif
