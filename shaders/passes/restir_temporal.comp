#version 460
// Pass `temporal`, gather mode (method restir-gather; Lin et al. 2022 section 7, as RS-main 3.3
// writes GRIS): the current primary hit (the visibility buffer) is backprojected with the previous camera and
// object transforms to the previous pixel q; q's reservoir (frame t-1) is shifted into this pixel
// (frame t) and resampled together with the canonical sample. MIS is the two-domain generalized
// balance heuristic (RS-main Eq. 6/7): the canonical sample is shifted back into q in frame t-1
// with the previous TLAS, transforms, camera and light totals, so both p-hat-from values are exact.
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

uint g_rays = 0u;

void count_shift(ShiftResult s) {
  g_rays += s.rays;
  counter_add(COUNTER_TEMPORAL_SHIFTS, 1u);
  if (s.reason != SHIFT_OK) counter_add(COUNTER_TEMPORAL_FAIL + s.reason, 1u);
  count_suffix(s, COUNTER_RAYS_REPLAY);
}

// Backprojection: the previous pixel q that saw this pixel's centre hit (the primary stage's
// visibility buffer) moved back with its object's previous transform, through the previous camera.
// For the biased option's validation also q's own centre hit in frame t-1 (load_previous_centre):
// the previous G-buffer sample the DI tutorial validates against, from the previous visibility buffer.
struct Backprojection {
  uvec2 q;                 // the history pixel: under s, or the one the history search chose
  vec2 s;                  // the backprojected position in the previous image (pixels)
  SurfaceHit centre;       // this pixel's centre hit, frame t
  ResolvedSurface before;  // its surface point in frame t-1 (render space of t-1: the previous camera at the origin)
  bool have_previous;      // q's centre ray hit something in frame t-1
  SurfaceHit previous;     // q's centre hit, frame t-1 (render space of t-1)
};

// The t-th previous pixel tried around the backprojected one (offset from it), nearest first:
// itself, its neighbours on the sides nearer to the backprojected position (along the nearer axis
// first), the diagonal between them, then the far sides and corners.
ivec2 temporal_try_offset(uint t, ivec2 step, bool x_first) {
  ivec2 a = x_first ? ivec2(step.x, 0) : ivec2(0, step.y);  // the nearer side
  ivec2 b = x_first ? ivec2(0, step.y) : ivec2(step.x, 0);
  const ivec2 order[9] = ivec2[9](ivec2(0), a, b, a + b, -a, -b, -a + b, a - b, -a - b);
  return order[min(t, 8u)];
}

bool backproject(uvec2 pixel, out Backprojection b) {
  b.have_previous = false;
  GpuPrimaryHit entry = b_primary[pixel_index(pixel)];
  SurfacePoint centre = primary_surface(entry);
  if (centre.instance == SURFACE_NONE) return false;
  b.centre = primary_surface_hit(false, entry);
  b.before = resolve_surface(true, centre);  // across a LoD switch: tau of the centre (LOD 4.4's motion vectors)
  count_lod_mapping(b.before);
  if (b.before.reason != RESOLVE_OK) return false;
  vec3 ndc = camera_ndc(u_frame.prev_camera, b.before.hit.position);
  if (!(ndc.z > 0.0)) return false;
  vec2 s = vec2((ndc.x + 1.0) * 0.5 * float(u_frame.prev_width), (1.0 - ndc.y) * 0.5 * float(u_frame.prev_height));
  if (!(s.x >= 0.0 && s.y >= 0.0 && s.x < float(u_frame.prev_width) && s.y < float(u_frame.prev_height))) return false;
  b.q = uvec2(s);
  b.s = s;
  return true;
}

// The history filter and search: whether q's centre surface in frame t-1 is like this pixel's
// centre surface moved back to frame t-1 (both at their distance from the previous camera); when it
// is not (its camera sample of frame t-1 found a blade or an edge that this pixel's does not), the
// other previous pixels around s are tried, nearest first (RESTIR_TEMPORAL_TRIES), and the first
// that is becomes q. Reads the visibility buffers only, never a reservoir, so the domain is still
// chosen independently of the samples.
bool find_history(inout Backprojection b) {
  CentreSurface now = surface_of(b.before, length(b.before.hit.position), camera_spread(true));
  vec2 f = fract(b.s);
  ivec2 step = ivec2(f.x < 0.5 ? -1 : 1, f.y < 0.5 ? -1 : 1);  // towards the nearer neighbours
  bool x_first = abs(f.x - 0.5) > abs(f.y - 0.5);
  for (uint t = 0u; t < RESTIR_TEMPORAL_TRIES; ++t) {
    ivec2 c = ivec2(uvec2(b.s)) + temporal_try_offset(t, step, x_first);
    if (c.x < 0 || c.y < 0 || c.x >= int(u_frame.prev_width) || c.y >= int(u_frame.prev_height)) continue;
    if (similar_surface(now, centre_surface(b_primary_prev[uint(c.y) * u_frame.prev_width + uint(c.x)]))) {
      b.q = uvec2(c);
      return true;
    }
  }
  return false;
}

void load_previous_centre(inout Backprojection b) {
  GpuPrimaryHit q_entry = b_primary_prev[b.q.y * u_frame.prev_width + b.q.x];
  b.have_previous = (q_entry.flags & PRIMARY_HIT) != 0u;
  if (b.have_previous) b.previous = primary_surface_hit(true, q_entry);
}

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

// Step 1, find the history: the previous pixel q whose reservoir is this pixel's history
// (backprojection, then the history filter's search), chosen from geometry alone; false when there
// is none. Whether domain q takes part depends on geometry only. An empty reservoir in q still
// claims its MIS share of the canonical sample (its confidence counts), it just brings no
// candidate. With the history filter, q takes part only when its centre surface is like this
// pixel's (find_history): a pixel that was disoccluded has no history, instead of the occluder's.
bool find_temporal_neighbor(uvec2 pixel, bool unbiased, out Backprojection bp) {
  bool have_history = backproject(pixel, bp);
  if (have_history && (u_restir.flags & RESTIR_TEMPORAL_FILTER) != 0u) have_history = find_history(bp);
  if (have_history && !unbiased) load_previous_centre(bp);  // the biased validation's, of the final q
  return have_history;
}

// Step 2, shift: the history sample into this pixel (frame t), and for the unbiased MIS the
// canonical sample back into q (frame t-1).
struct TemporalShifts {
  ShiftResult forward;  // T(y_h): the history sample in this pixel
  float from_q;         // p-hat from q of the canonical sample (RS-main Eq. 7): p-hat_q(T^-1(y_c)) |dT^-1/dy_c|
};

TemporalShifts shift_temporal(uvec2 pixel, uvec2 q, Reservoir canonical, Reservoir history, bool unbiased) {
  bool moved = (u_frame.history_flags & HISTORY_SCENE_MOVED) != 0u;
  TemporalShifts t;
  t.forward = shift_none(SHIFT_FAIL_ZERO);
  t.from_q = 0.0;
  // Both shifts run through one call site (lavapipe compiles each inlined call separately):
  // job 0, the history sample into this pixel (frame t); job 1, the canonical sample back into q
  // (frame t-1), needed only for the unbiased MIS.
  for (uint job = 0u; job < (unbiased ? 2u : 1u); ++job) {
    bool back = job == 1u;
    if (!back && !reservoir_valid(history)) {
      t.forward = shift_fail(t.forward, SHIFT_FAIL_ZERO);
      continue;
    }
    if (back && !reservoir_valid(canonical)) break;
    // The target domain's primary vertex: this pixel's in frame t, q's in frame t-1. (An if, not a
    // ?: between the two buffers: glslang then stores one block's struct type into the other's.)
    GpuPrimaryHit target = b_primary[pixel_index(pixel)];
    if (back) target = b_primary_prev[q.y * u_frame.prev_width + q.x];
    DomainPrimary dp = domain_primary(target);
    ShiftResult s = shift_path(back, back ? vec2(q) : vec2(pixel), dp, back ? canonical.y : history.y, moved);
    count_shift(s);
    if (!back) t.forward = s;
    else if (s.reason == SHIFT_OK) t.from_q = p_hat_from(luminance(s.f), s.jacobian);
  }
  return t;
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
  bool have_history = find_temporal_neighbor(pixel, unbiased, bp);
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
  TemporalShifts sh = shift_temporal(pixel, q, canonical, history, unbiased);
  ShiftResult fw = sh.forward;
  // The history sample in this pixel: w_h = m_h p-hat(y') W_h |dy'/dy| (RS-main Eq. 4).
  float p_fw = fw.reason == SHIFT_OK ? luminance(fw.f) : 0.0;
  float jacobian = fw.reason == SHIFT_OK ? fw.jacobian : 0.0;

  // 3. MIS weights.
  TemporalWeights w = unbiased ? temporal_weights_unbiased(canonical, history, c_c, c_h, p_fw, jacobian, sh.from_q)
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
