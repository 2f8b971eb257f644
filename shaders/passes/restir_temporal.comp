#version 460
// Pass `temporal`, gather mode (method restir-gather; Lin et al. 2022 section 7, as RS-main 3.3
// writes GRIS): the current primary hit (the visibility buffer) is backprojected with the previous camera and
// object transforms to the previous pixel q; q's reservoir (frame t-1) is shifted into this pixel
// (frame t) and resampled together with the canonical sample. MIS is the two-domain generalized
// balance heuristic (RS-main Eq. 6/7): the canonical sample is shifted back into q in frame t-1
// with the previous TLAS, transforms, camera and light totals, so both p-hat-from values are exact.
// That reverse shift is a pass of its own before this one (restir_temporal_reverse.comp), which
// leaves its p-hat-from in BINDING_TEMPORAL_FROM_Q: a shift that may run in either frame compiles
// for both (lavapipe: about 60 s of LLVM against 27 s for each frame's alone), and the two passes
// compile in parallel.
// The biased option replaces this with the DI tutorial's confidence weights (its merge weight
// p-hat_cur * W_prev * min(M_prev, M_max)) and heuristic validation (material, normal, position,
// target ratio in [0.1, 10]).
#extension GL_EXT_ray_query : require
#extension GL_GOOGLE_include_directive : require

layout(local_size_x = 8, local_size_y = 8, local_size_z = 1) in;

#define STRATA_HISTORY 1
#include "include/scene_bridge.glsl"
#include "restir/restir_pass.glsl"
#include "restir/path_space.glsl"
#include "restir/centre_surface.glsl"
#include "restir/restir_limits.h"

layout(set = 0, binding = BINDING_RESERVOIRS_IN, std430) readonly buffer ReservoirsIn { PackedReservoir b_in[]; };
layout(set = 0, binding = BINDING_PRIMARY, std430) readonly buffer Primary { GpuPrimaryHit b_primary[]; };
layout(set = 0, binding = BINDING_PRIMARY_PREV, std430) readonly buffer PrimaryPrev { GpuPrimaryHit b_primary_prev[]; };
// Unbiased MIS: per pixel, p-hat from q of the canonical sample (restir_temporal_reverse.comp).
layout(set = 0, binding = BINDING_TEMPORAL_FROM_Q, std430) readonly buffer FromQ { float b_from_q[]; };

#include "restir/temporal_history.glsl"

// The tutorial's validation of the history for the current pixel (DI tutorial section 5): the
// previous pixel's centre surface against the current one (material, normal, position relative to
// the distance from the camera), and the target ratio p-hat(y_prev at x) / p-hat(y_prev at x_prev)
// in [0.1, 10].
bool heuristic_valid(Backprojection b, float p_hat_current, float p_hat_previous) {
  if (!b.have_previous) return false;
  float ratio = p_hat_current / p_hat_previous;
  return b.previous.material == b.centre.material && dot(b.previous.geo_normal, b.centre.geo_normal) > 0.9 &&
         length(b.previous.position - b.before.hit.position) < 0.05 * length(b.before.hit.position) && ratio >= 0.1 &&
         ratio <= 10.0;
}

// Step 2, shift: the history sample into this pixel (frame t), T(y_h). (The unbiased MIS's reverse
// shift, of the canonical sample back into q in frame t-1, ran in restir_temporal_reverse.comp.)
ShiftResult shift_temporal(uvec2 pixel, Reservoir history) {
  if (!reservoir_valid(history)) return shift_fail(shift_none(SHIFT_FAIL_ZERO), SHIFT_FAIL_ZERO);
  bool moved = (u_frame.history_flags & HISTORY_SCENE_MOVED) != 0u;
  ShiftResult s = shift_path(false, vec2(pixel), domain_primary(b_primary[pixel_index(pixel)], pixel_index(pixel)), history.y, moved);
  count_shift(s);
  return s;
}

// Step 3, the MIS weights: the resampling weights of the canonical sample (w_c) and of the history
// sample in this pixel (w_h), and the history's confidence as it is streamed.
struct TemporalWeights {
  float w_c;
  float w_h;
  float c_h;
};

// Unbiased: the generalized balance heuristic over the two domains (RS-main Eq. 6/7), with
// w = m p-hat W |J| (RS-main Eq. 4). p_fw and jacobian are those of the history sample shifted here.
TemporalWeights temporal_weights_unbiased(Reservoir canonical, Reservoir history, float c_c, float c_h, float p_fw,
                                          float jacobian, float from_q) {
  TemporalWeights w;
  w.c_h = c_h;
  // p-hat from q of y': p-hat_q(y) |dy/dy'| = p-hat_q(y) / |dy'/dy|.
  float m_h = jacobian > 0.0 ? mis_balance2(c_h, history.p_hat / jacobian, c_c, p_fw) : 0.0;
  w.w_h = m_h * p_fw * history.ucw * jacobian;
  float m_c = mis_balance2(c_c, canonical.p_hat, c_h, from_q);
  w.w_c = m_c * canonical.p_hat * canonical.ucw;
  return w;
}

// Biased: the tutorial's merge: every domain counts with its confidence (its M) and no MIS. The
// history is merged only when q's surface passes the heuristic validation; a history without a
// sample (its candidates were all zero, e.g. in shadow) then counts its confidence with weight 0,
// as the tutorial's M_prev does.
TemporalWeights temporal_weights_biased(Backprojection bp, Reservoir canonical, Reservoir history, float c_c, float c_h,
                                        float p_fw, float jacobian) {
  TemporalWeights w;
  w.c_h = c_h;
  bool has_sample = reservoir_valid(history);
  bool valid = has_sample ? (p_fw > 0.0 && heuristic_valid(bp, p_fw, history.p_hat)) : heuristic_valid(bp, 1.0, 1.0);
  if (!valid) counter_add(COUNTER_TEMPORAL_INVALID, 1u);
  if (!valid) w.c_h = 0.0;  // refused: neither its sample nor its confidence is merged
  float total = c_c + w.c_h;
  w.w_h = valid && has_sample ? (w.c_h / total) * p_fw * history.ucw * jacobian : 0.0;
  w.w_c = (c_c / total) * canonical.p_hat * canonical.ucw;
  return w;
}

void main() {
  uvec2 pixel = gl_GlobalInvocationID.xy;
  if (pixel.x >= u_frame.width || pixel.y >= u_frame.height) return;
  uint index = domain_of(pixel, 0u);
  Reservoir canonical = unpack_reservoir(b_out[index]);
  vec3 f_canonical = b_contribution[index].rgb;
  bool unbiased = (u_restir.flags & RESTIR_UNBIASED) != 0u;

  // 1. Find the history.
  Backprojection bp;
  Reservoir history = reservoir_empty();
  bool have_history = find_temporal_neighbor(pixel, unbiased, true, bp);
  uvec2 q = bp.q;
  if (have_history) history = unpack_reservoir(b_in[prev_domain_of(q, 0u)]);
  if (!have_history || !(history.confidence > 0.0)) {
    counter_add(COUNTER_TEMPORAL_NO_HISTORY, 1u);
    counter_add(COUNTER_RAYS_TEMPORAL, g_rays);
    return;  // the canonical reservoir and its estimate stay in place
  }
  float c_c = canonical.confidence;
  float c_h = confidence_capped(history.confidence, confidence_cap_of(b_primary[pixel_index(pixel)]));  // RS-main 3.4

  // 2. Shift.
  ShiftResult fw = shift_temporal(pixel, history);
  // p-hat from q of the canonical sample (RS-main Eq. 7): p-hat_q(T^-1(y_c)) |dT^-1/dy_c|.
  float from_q = unbiased ? b_from_q[pixel_index(pixel)] : 0.0;
  // The history sample in this pixel: w_h = m_h p-hat(y') W_h |dy'/dy| (RS-main Eq. 4).
  float p_fw = fw.reason == SHIFT_OK ? luminance(fw.f) : 0.0;
  float jacobian = fw.reason == SHIFT_OK ? fw.jacobian : 0.0;

  // 3. MIS weights.
  TemporalWeights w = unbiased ? temporal_weights_unbiased(canonical, history, c_c, c_h, p_fw, jacobian, from_q)
                               : temporal_weights_biased(bp, canonical, history, c_c, c_h, p_fw, jacobian);

  // 4. Stream the canonical sample, then the history.
  Rng rng = frame_rng(pixel_index(pixel), RNG_SALT_TEMPORAL_SELECT);
  GrisState s = gris_begin();
  gris_stream_path(s, w.w_c, canonical.p_hat, f_canonical, c_c, 0u, rng_next_float(rng));
  gris_stream_path(s, w.w_h, p_fw, fw.f, w.c_h, 1u, rng_next_float(rng));
  Reservoir selected = canonical;
  vec3 f = f_canonical;
  if (s.selected == 1u) {
    selected = history;
    selected.y = shifted_sample(history.y, fw);
    f = fw.f;
    counter_add(COUNTER_TEMPORAL_SELECTED, 1u);
  }

  // 5. Finalise.
  finalise_reservoir(index, s, selected, f, s.confidence);
  counter_add(COUNTER_RAYS_TEMPORAL, g_rays);
}
