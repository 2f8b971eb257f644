// Generalized resampled importance sampling (GRIS, Lin et al. 2022) as RS-main section 3.3 writes it:
// streaming selection with resampling weights w_i (Eq. 4), the unbiased contribution weight of the
// selected sample (Eq. 5), the generalized balance heuristic (Eq. 6) over "p-hat from" values
// (Eq. 7), confidence-weighted pairwise MIS, and the confidence cap (RS-main 3.4).
// Every weight passes through gris_sanitize: NaN, Inf or negative values make it 0 (docs/ARCHITECTURE.md, Robustness).
#ifndef STRATA_RESTIR_GRIS_H
#define STRATA_RESTIR_GRIS_H
#include "include/lang.h"
#include "restir/thresholds.h"

STRATA_NAMESPACE_BEGIN

// A weight that is not a finite non-negative number is a failed shift: weight 0.
INLINE float gris_sanitize(float w) { return (w >= 0.0f && !isinf(w)) ? w : 0.0f; }
INLINE bool gris_valid(float w) { return w >= 0.0f && !isinf(w); }

// Streaming resampling state: which candidate is selected, and the running sums.
struct GrisState {
  float weight_sum;       // sum of resampling weights w_i
  float selected_p_hat;   // p-hat of the selected candidate in the target domain
  float confidence;       // sum of the inputs' confidence weights
  uint selected;          // caller-defined index of the selected candidate (0xFFFFFFFF: none)
  uint rejected;          // candidates whose weight was not finite (counted in the statistics)
  vec3 estimate;          // sum_i w_i f(Y_i) / p-hat(Y_i): see gris_stream_path
};

CONST_DEF uint GRIS_NONE = 0xFFFFFFFFu;

INLINE GrisState gris_begin() {
  GrisState s;
  s.weight_sum = 0.0f;
  s.selected_p_hat = 0.0f;
  s.confidence = 0.0f;
  s.selected = GRIS_NONE;
  s.rejected = 0u;
  s.estimate = vec3(0.0f);
  return s;
}

// RS-main Eq. 4: w_i = m_i(Y_i) p-hat(Y_i) W_{X_i} |dT_i/dX_i|.
INLINE float gris_resampling_weight(float mis, float p_hat, float ucw, float jacobian) {
  return mis * p_hat * ucw * jacobian;
}

// Streams one candidate with resampling weight w; u uniform in [0,1) decides the selection.
// Returns true when the candidate becomes the selected one. A zero weight adds only confidence.
INLINE bool gris_stream(INOUT(GrisState) s, float w, float p_hat, float confidence, uint index, float u) {
  s.confidence += confidence;
  if (!gris_valid(w) || !gris_valid(p_hat)) {
    s.rejected += 1u;
    return false;
  }
  if (w <= 0.0f) return false;
  s.weight_sum += w;
  if (u * s.weight_sum < w) {
    s.selected = index;
    s.selected_p_hat = p_hat;
    return true;
  }
  return false;
}

// gris_stream for a candidate path whose contribution f(Y_i) is known; also accumulates the
// pixel estimate over all candidates. With W_Y from Eq. 5 and P(select i) = w_i / sum_j w_j:
//   E[f(Y) W_Y | Y_1..Y_M] = sum_i (w_i / sum_j w_j) f(Y_i) (sum_j w_j / p-hat(Y_i)) = sum_i w_i f(Y_i) / p-hat(Y_i),
// so shading with the sum instead of f(Y) W_Y has the same expectation (unbiased wherever the
// selected sample's estimate is) and never more variance: it conditions out the random selection,
// including the choice of colour under a luminance target (Rao-Blackwellisation of RIS). The
// reservoir still keeps the selected Y for the next reuse; only the pixel is shaded with the sum.
INLINE bool gris_stream_path(INOUT(GrisState) s, float w, float p_hat, vec3 f, float confidence, uint index, float u) {
  bool selected = gris_stream(s, w, p_hat, confidence, index, u);
  if (gris_valid(w) && w > 0.0f && p_hat > 0.0f && !isinf(p_hat)) s.estimate += f * gris_sanitize(w / p_hat);
  return selected;
}

// RS-main Eq. 5: W_Y = (1 / p-hat(Y)) sum_i w_i. Zero when nothing was selected or p-hat is 0.
INLINE float gris_ucw(GrisState s) {
  if (s.selected == GRIS_NONE || !(s.selected_p_hat > 0.0f)) return 0.0f;
  return gris_sanitize(s.weight_sum / s.selected_p_hat);
}

// Confidence after resampling: the capped sum (RS-main 3.4; default cap 20).
INLINE float confidence_capped(float confidence_sum, float cap) { return min(confidence_sum, cap); }

// RS-main Eq. 7, "p-hat from": the target function of domain j at the path shifted back into it,
// times the Jacobian of that inverse shift. A failed inverse shift passes jacobian_inverse = 0.
INLINE float p_hat_from(float p_hat_in_domain_j, float jacobian_inverse) {
  return gris_sanitize(p_hat_in_domain_j * jacobian_inverse);
}

// RS-main Eq. 6 from its terms c_j p-hat_from_j: the weight self / (self + other + third) of one
// domain among up to three (RS-main Eq. 11 and 13; RS-supp Eq. 20-22 with the backup domain);
// 0 when that is not a finite number in [0, 1].
INLINE float mis_balance_terms(float self_term, float other_term, float third_term) {
  float d = self_term + other_term + third_term;
  if (!(d > 0.0f) || isinf(d)) return 0.0f;
  return self_term / d;
}

// RS-main Eq. 6 for two domains (canonical c, and one other o), as in the temporal pass: the
// weight of domain `self` for a path whose p-hat-from values are known.
INLINE float mis_balance2(float c_self, float p_from_self, float c_other, float p_from_other) {
  return mis_balance_terms(c_self * p_from_self, c_other * p_from_other, 0.0f);
}

// Confidence-weighted pairwise MIS over a canonical domain and k neighbours. Each pair
// (canonical, neighbour i) is a two-strategy balance heuristic in which the canonical domain brings
// c_c / k of its confidence; pair i carries the share (c_i + c_c / k) / C of the total confidence C.
// Weights therefore sum to one over all strategies for every path: O(k) shifts instead of the
// O(k^2) of the generalized balance heuristic (Bitterli 2022; Lin et al. 2022, section 6).
//
// Neighbour i's sample y_i: m_i = share_i * c_i p_i(y_i) / (c_i p_i(y_i) + (c_c / k) p_c(y_i)).
INLINE float mis_pairwise_neighbor(float c_i, float p_from_i, float c_canonical, float p_canonical, float k,
                                   float confidence_total) {
  if (!(k > 0.0f) || !(confidence_total > 0.0f)) return 0.0f;
  float cc = c_canonical / k;
  float share = (c_i + cc) / confidence_total;
  return share * mis_balance2(c_i, p_from_i, cc, p_canonical);
}

// The canonical sample's weight is the sum over pairs of the canonical side: callers accumulate
// this term for each neighbour i, evaluated at the canonical sample y_c.
INLINE float mis_pairwise_canonical_term(float c_i, float p_from_i_at_canonical, float c_canonical, float p_canonical,
                                         float k, float confidence_total) {
  if (!(k > 0.0f) || !(confidence_total > 0.0f)) return 0.0f;
  float cc = c_canonical / k;
  float share = (c_i + cc) / confidence_total;
  return share * mis_balance2(cc, p_canonical, c_i, p_from_i_at_canonical);
}

STRATA_NAMESPACE_END
#endif
