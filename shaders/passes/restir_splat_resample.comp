#version 460
// Pass `splat_resample` (restir-splat; RS-supp 3.1 step 4, the per-pixel resampling loop): GRIS of
// the canonical sample Y* with every previous reservoir splatted into this pixel (RS-main 4.1.2).
//   splat Y_i = T(X_i):  w_i = m_i(Y_i) p-hat(Y_i) W_{X_i} |T'(X_i)|                   (Eq. 10)
//                        m_i = c_i p-hat_prev(X_i) / |T'| / (c* p-hat(Y_i) + c_i p-hat_prev(X_i) / |T'|)  (Eq. 11)
//   canonical:           w* = m* p-hat(Y*) W_{Y*}                                       (Eq. 12)
//                        m* = c* p-hat(Y*) / (c* p-hat(Y*) + c_r p-hat_prev(T^-1 Y*) |T^-1'|)          (Eq. 13)
// where T^-1 Y* is the canonical sample reverse-splatted into the previous frame and c_r the
// confidence of the previous pixel it lands in. The output confidence is that of RS-main 4.3
// (Eq. 17): c* plus the bilinear interpolation of the previous confidences at the backprojected
// pixel centre, capped.
// restir-splat-backup (RS-main 4.2) adds the backup sample: the reservoir of the previous pixel b
// that the pixel centre backprojects into, gather-shifted here (T_b). Its MIS (RS-supp Eq. 20-22)
// adds the backup domain's term to every weight: T_b^-1 of each candidate into b, and the reverse
// splat of Y^b; confidences are split with alpha = 0.5 (RS-supp 3.2).
// restir-multilayer (ML 4.1, Sec. 5) resamples every active domain (pixel, layer): the image dispatch
// the front layer, a second dispatch (SPEC_DOMAIN_LIST) the compacted list of active deep domains.
// A reverse splat lands in the previous frame's domain that the layer rule of restir/layers.glsl
// picks there, and the confidence of Eq. 17 is read, at each bilinear tap, from the previous domain
// whose depth range holds the backprojected representative hit.
#extension GL_EXT_ray_query : require
#extension GL_GOOGLE_include_directive : require

layout(local_size_x = 8, local_size_y = 8, local_size_z = 1) in;

#define STRATA_HISTORY 1
#include "include/scene_bridge.glsl"
#include "restir/restir_pass.glsl"
#include "restir/splat.glsl"
#include "restir/splat_data.h"

layout(set = 0, binding = BINDING_RESERVOIRS_IN, std430) readonly buffer ReservoirsIn { PackedReservoir b_in[]; };
layout(set = 0, binding = BINDING_SPLATS, std430) readonly buffer Splats { SplatRecord b_splats[]; };
layout(set = 0, binding = BINDING_SPLAT_OFFSETS, std430) readonly buffer Offsets { uint b_offsets[]; };
layout(set = 0, binding = BINDING_SPLAT_LIST, std430) readonly buffer List { uint b_list[]; };
layout(set = 0, binding = BINDING_PRIMARY, std430) readonly buffer Primary { GpuPrimaryHit b_primary[]; };
layout(set = 0, binding = BINDING_DOMAIN_LIST, std430) readonly buffer DomainList { uint b_domain_list[]; };
layout(set = 0, binding = BINDING_DOMAIN_ARGS, std430) readonly buffer DomainArgs { GpuDomainArgs b_domain_args; };
layout(constant_id = SPEC_DOMAIN_LIST) const bool k_domain_list = false;

// The confidence of previous domain (q, layer), capped with `cap`: this domain's (confidence_cap_of its
// representative hit). Every previous domain's confidence enters this domain's MIS weights with the
// same cap, so the weights of each path still sum to one (a confidence weight may depend on the
// domain the path is in). Outside the image, or with no layer (LAYERS_MAX), 0.
float prev_confidence(ivec2 q, uint layer, float cap) {
  if (q.x < 0 || q.y < 0 || q.x >= int(u_frame.prev_width) || q.y >= int(u_frame.prev_height) || layer >= u_restir.layers) return 0.0;
  return confidence_capped(unpack_reservoir(b_in[prev_domain_of(uvec2(q), layer)]).confidence, cap);
}

// The same at a bilinear tap of Eq. 17 for a point at distance d from the previous camera: with
// pixel layers, the previous domain whose depth range holds d (ML Sec. 5); else the front layer.
float prev_confidence_at(ivec2 q, float d, float cap) {
  if (!multilayer()) return prev_confidence(q, 0u, cap);
  if (q.x < 0 || q.y < 0 || q.x >= int(u_frame.prev_width) || q.y >= int(u_frame.prev_height)) return 0.0;
  return prev_confidence(q, layer_by_range(true, uvec2(q), d), cap);
}

// The backprojection of this domain's representative hit (the pixel-centre hit of its layer, moved
// back with its object's previous transform) into the previous image; ok = false when it sees
// nothing, changed LoD level, or falls outside. `confidence` is RS-main 4.3's (Eq. 17) bilinear
// interpolation of the previous confidences there; `backup` the previous pixel it falls in (RS-main
// 4.2's rounded motion vector).
struct Backprojection {
  bool ok;
  uvec2 backup;
  float distance;  // from the previous camera
  float confidence;
};

Backprojection backproject_centre(GpuPrimaryHit centre, float cap) {
  Backprojection bp;
  bp.ok = false;
  bp.backup = uvec2(0u);
  bp.distance = 0.0;
  bp.confidence = 0.0;
  ResolvedSurface before = resolve_surface(true, primary_surface(centre));
  if (before.reason != RESOLVE_OK) return bp;
  vec3 p = before.hit.position;
  vec2 sub;
  if (!project(u_frame.prev_camera, u_frame.prev_width, u_frame.prev_height, p, vec3(0.0), bp.backup, sub)) return bp;
  bp.ok = true;
  float d = length(p);  // from the previous camera (the origin of its render space)
  bp.distance = d;
  vec2 s = vec2(bp.backup) + sub - 0.5;  // continuous coordinates of pixel centres
  ivec2 b = ivec2(floor(s));
  vec2 t = s - vec2(b);
  bp.confidence = (1.0 - t.x) * (1.0 - t.y) * prev_confidence_at(b, d, cap) + t.x * (1.0 - t.y) * prev_confidence_at(b + ivec2(1, 0), d, cap) +
                  (1.0 - t.x) * t.y * prev_confidence_at(b + ivec2(0, 1), d, cap) + t.x * t.y * prev_confidence_at(b + ivec2(1, 1), d, cap);
  return bp;
}

// The backup domain b of this domain (RS-main 4.2), in the previous frame: restir-splat-backup's is
// the front layer of the previous pixel the centre backprojects into. restir-multilayer's deep backup
// (RESTIR_DEEP_BACKUP; docs/ARCHITECTURE.md, "Pixel layers": the deep backup) extends it to pixel layers: a
// disoccluded front pixel whose centre hit an active previous deep domain held (DOMAIN_HELD, a
// geometric flag of domain_build) takes that deep domain, the one whose depth range holds the
// backprojected hit, as its backup; its gather shifts are restricted to the domain of ML Eq. 4.
struct BackupDomain {
  bool ok;
  uint layer;
  float t_min;  // its depth range (0, RAY_UNBOUNDED for the front layer)
  float t_max;
};

BackupDomain backup_domain_of(uint index, uint layer, Backprojection bp) {
  BackupDomain b;
  b.ok = false;
  b.layer = 0u;
  b.t_min = 0.0;
  b.t_max = RAY_UNBOUNDED;
  if (!bp.ok) return b;
  if ((u_restir.flags & RESTIR_SPLAT_BACKUP) != 0u) {
    b.ok = true;
    return b;
  }
  if ((u_restir.flags & RESTIR_DEEP_BACKUP) == 0u || k_layer_stepping || layer != 0u || (b_domains[index].flags & DOMAIN_HELD) == 0u)
    return b;
  b.layer = deep_layer_by_range(true, bp.backup, bp.distance, b.t_min, b.t_max);
  b.ok = b.layer != 0u;
  return b;
}

// The next splat record that landed in this pixel after record `after` (all of them when `first_pick`):
// the insert pass's atomics leave a pixel's list in any order, and the resampling below streams the
// splats in increasing record order (previous pixel, then time partition), so that a frame is
// reproducible bit for bit. A pixel holds few splats (splat.max_per_pixel), so the scan is cheap
// next to the shifts.
uint next_splat(uint first, uint last, uint after, bool first_pick) {
  uint best = SPLAT_NONE;
  for (uint i = first; i < last; ++i) {
    uint r = b_list[i];
    if ((first_pick || r > after) && r < best) best = r;
  }
  return best;
}

void count_shift(ShiftResult r) {
  counter_add(COUNTER_TEMPORAL_SHIFTS, 1u);
  counter_add(COUNTER_RAYS_TEMPORAL, r.rays);
  if (r.reason != SHIFT_OK) counter_add(COUNTER_TEMPORAL_FAIL + r.reason, 1u);
  count_suffix(r, COUNTER_RAYS_REPLAY_RESAMPLE);
}

// This invocation's domain: the front layer's at its pixel (the image dispatch), or an entry of the
// active deep domains' list (SPEC_DOMAIN_LIST; one thread per entry, DOMAIN_LIST_GROUP per workgroup).
bool invocation_domain(out uint domain) {
  if (k_domain_list) {
    uint i = gl_WorkGroupID.x * DOMAIN_LIST_GROUP + gl_LocalInvocationIndex;
    domain = i < b_domain_args.count ? b_domain_list[i] : 0u;
    return i < b_domain_args.count;
  }
  uvec2 pixel = gl_GlobalInvocationID.xy;
  domain = domain_of(pixel, 0u);
  return pixel.x < u_frame.width && pixel.y < u_frame.height;
}

// The shift jobs of a domain, in the order they run: every shift is a job of one loop with one
// shift_path call (lavapipe inlines a traversal per call site).
const uint JOB_REVERSE = 0u;                // Y*, the canonical sample, reverse-splatted into the previous front layer (Eq. 13/21)
const uint JOB_REVERSE_DEEPER = 1u;         // the same into the deeper previous domain whose range holds it, when JOB_REVERSE found it hidden (restir-multilayer)
const uint JOB_CANONICAL_TO_BACKUP = 2u;    // Y* into the backup domain (RS-supp Eq. 21)
const uint JOB_BACKUP = 3u;                 // the backup sample into this pixel: Y^b
const uint JOB_BACKUP_REVERSE = 4u;         // Y^b reverse-splatted (RS-supp Eq. 22)
const uint JOB_BACKUP_REVERSE_DEEPER = 5u;  // the same deeper, when JOB_BACKUP_REVERSE found it hidden
const uint JOB_SPLATS = 6u;                 // then per splat s: Y_s into the backup domain (RS-supp Eq. 20), and its resampling

// A reverse splat of the canonical sample or of Y^b (RS-main Eq. 13): where it landed in the
// previous frame, for the MIS weights.
struct ReverseSplat {
  ShiftJob job;        // the front-layer attempt, which the deeper job retries
  ShiftResult result;  // its result
  float from;          // p-hat_prev(T^-1 Y) |dT^-1/dY|
  float confidence;    // (1 - alpha) times the confidence of the previous domain it landed in
};

ReverseSplat reverse_splat_none() {
  ReverseSplat r;
  r.job.ok = false;
  r.result = shift_none(SHIFT_FAIL_ZERO);
  r.from = 0.0;
  r.confidence = 0.0;
  return r;
}

// The backup sample's shifts (RS-main 4.2).
struct BackupShifts {
  ShiftResult y;    // Y^b: the backup sample shifted into this pixel
  float jacobian;   // its |T_b'| (0: failed)
  float from_star;  // p-hat_prev(T_b^-1 Y*) |dT_b^-1/dY*|
};

void main() {
  uint index;
  if (!invocation_domain(index)) return;
  uvec2 pixel = domain_pixel_of(index);
  uint layer = domain_layer_of(index);
  Reservoir canonical = unpack_reservoir(b_out[index]);
  vec3 f_canonical = b_contribution[index].rgb;
  float c_star = canonical.confidence;
  bool moved = (u_frame.history_flags & HISTORY_SCENE_MOVED) != 0u;
  bool with_backup = (u_restir.flags & RESTIR_SPLAT_BACKUP) != 0u;
  // The cap of this domain (RS-main 3.4): still_confidence_cap where the camera and the instance its
  // representative hit lies on did not move, else confidence_cap (docs/ARCHITECTURE.md, "Confidence cap").
  GpuPrimaryHit centre = b_primary[index];  // the visibility buffer is indexed by domain (layer 0: by pixel)
  float cap = confidence_cap_of(centre);
  // 1. Find the history: the splats that landed here (the counting sort's list), the backprojected
  // representative hit (Eq. 17's confidence) and the backup domain.
  Backprojection bp = backproject_centre(centre, cap);
  BackupDomain bd = backup_domain_of(index, layer, bp);
  bool backup_domain = bd.ok;
  // RS-supp 3.2: with the backup, backup-domain confidences are scaled by alpha and splat-domain
  // ones by 1 - alpha (alpha = 0.5). The same scale applies to a domain in every weight below, so
  // the weights of every path still sum to one.
  float alpha = with_backup || backup_domain ? 0.5 : 0.0;
  Reservoir xb = backup_domain ? unpack_reservoir(b_in[prev_domain_of(bp.backup, bd.layer)]) : reservoir_empty();
  float c_b = backup_domain ? alpha * confidence_capped(xb.confidence, cap) : 0.0;

  // 2-4. Shift, MIS weights, stream.
  Rng rng = frame_rng(index, RNG_SALT_SPLAT_SELECT);  // per domain (layer 0: the pixel)
  GrisState st = gris_begin();
  Reservoir out_r = canonical;
  vec3 f = f_canonical;
  uint first = b_offsets[index];
  uint last = b_offsets[index + 1u];

  ReverseSplat rev_star = reverse_splat_none();  // Y*'s
  ReverseSplat rev_b = reverse_splat_none();     // Y^b's
  BackupShifts bk;
  bk.y = shift_none(SHIFT_FAIL_ZERO);
  bk.jacobian = 0.0;
  bk.from_star = 0.0;
  bool from_deep = false;   // a splat from a previous deep domain landed here
  uint jobs = JOB_SPLATS + (last - first);
  uint record = SPLAT_NONE;
  for (uint job = 0u; job < jobs; ++job) {
    uint s = job >= JOB_SPLATS ? first + job - JOB_SPLATS : 0u;
    SplatRecord rec;
    Reservoir y_s;
    if (job >= JOB_SPLATS) {
      record = next_splat(first, last, record, job == JOB_SPLATS);
      rec = b_splats[record];
      y_s = unpack_reservoir(rec.reservoir);
      from_deep = from_deep || record % prev_domain_count() >= u_frame.prev_width * u_frame.prev_height;
    }
    ShiftJob sj;
    sj.ok = false;
    bool run = false;
    // The two reverse splats: one splat_prepare call site for both (each site inlines tau's
    // UV-space queries, which lavapipe compiles for minutes).
    if (job == JOB_REVERSE || job == JOB_BACKUP_REVERSE) {
      run = job == JOB_REVERSE ? reservoir_valid(canonical) : bk.jacobian > 0.0;
      PathSample y_splat = job == JOB_REVERSE ? canonical.y : shifted_sample(xb.y, bk.y);  // Y^b, the backup sample as shifted into this pixel
      if (run) sj = splat_prepare(true, y_splat, 0u);
      if (job == JOB_REVERSE) rev_star.job = sj;
      else rev_b.job = sj;
    } else if (job == JOB_REVERSE_DEEPER || job == JOB_BACKUP_REVERSE_DEEPER) {
      ShiftJob deeper = job == JOB_REVERSE_DEEPER ? rev_star.job : rev_b.job;  // one splat_deeper call site
      run = deeper.ok && splat_deeper(deeper, job == JOB_REVERSE_DEEPER ? rev_star.result : rev_b.result);
      if (run) {
        sj = deeper;
        counter_add(k_layer_stepping ? COUNTER_SPLAT_STEP_RAYS : COUNTER_SPLAT_RANGE_RAYS, 1u);  // the query after the layer test
      }
    } else if (job == JOB_BACKUP) {
      run = backup_domain && reservoir_valid(xb);
      if (run) sj = gather_prepare(false, vec2(pixel), xb.y);
    } else {
      // Y* and the splats into the backup domain (for the deep backup restricted to its range).
      run = backup_domain && (job != JOB_CANONICAL_TO_BACKUP || reservoir_valid(canonical));
      if (run)
        sj = gather_prepare_deep(true, vec2(bp.backup), job == JOB_CANONICAL_TO_BACKUP ? canonical.y : y_s.y, bd.layer, bd.t_min, bd.t_max);
    }
    ShiftResult r;
    r.reason = SHIFT_FAIL_ZERO;
    float jac = 0.0;
    if (run) {
      uint hidden_rays = 0u;
      r = gather_hidden(sj, hidden_rays) ? run_shift(sj, moved) : shift_none(SHIFT_FAIL_PRIMARY);
      r.rays += hidden_rays;
      jac = shift_finish(sj, r);
      count_shift(r);
    }
    float from = jac > 0.0 ? p_hat_from(luminance(r.f), jac) : 0.0;
    if (job <= JOB_REVERSE_DEEPER) {
      if (job == JOB_REVERSE) rev_star.result = r;
      if (jac > 0.0) {
        rev_star.from = from;
        rev_star.confidence = (1.0 - alpha) * prev_confidence(ivec2(sj.pixel), sj.layer, cap);
      }
    } else if (job == JOB_CANONICAL_TO_BACKUP) {
      bk.from_star = from;
    } else if (job == JOB_BACKUP) {
      bk.y = r;
      bk.jacobian = jac;
    } else if (job == JOB_BACKUP_REVERSE || job == JOB_BACKUP_REVERSE_DEEPER) {
      if (job == JOB_BACKUP_REVERSE) rev_b.result = r;
      if (jac > 0.0) {
        rev_b.from = from;
        rev_b.confidence = (1.0 - alpha) * prev_confidence(ivec2(sj.pixel), sj.layer, cap);
      }
      if (job == JOB_BACKUP_REVERSE) continue;
      // Every term of the canonical sample's and the backup's weights is known: stream both.
      // The canonical sample (RS-main Eq. 12-13; RS-supp Eq. 21) and the backup (RS-supp Eq. 22).
      float m_star = mis_balance_terms(c_star * canonical.p_hat, c_b * bk.from_star, rev_star.confidence * rev_star.from);
      gris_stream_path(st, m_star * canonical.p_hat * canonical.ucw, canonical.p_hat, f_canonical, c_star, 0u, rng_next_float(rng));
      float p_yb = bk.jacobian > 0.0 ? luminance(bk.y.f) : 0.0;
      float m_b = bk.jacobian > 0.0 ? mis_balance_terms(c_b * xb.p_hat / bk.jacobian, c_star * p_yb, rev_b.confidence * rev_b.from) : 0.0;
      if (gris_stream_path(st, m_b * p_yb * xb.ucw * bk.jacobian, p_yb, bk.y.f, 0.0, 1u, rng_next_float(rng))) {
        out_r = xb;
        out_r.y = shifted_sample(xb.y, bk.y);
        f = bk.y.f;
      }
    } else {
      // Splat Y_s (RS-main Eq. 10-11; RS-supp Eq. 20).
      vec3 f_y = rec.f_jacobian.xyz;
      float jacobian = rec.f_jacobian.w;
      float p_y = luminance(f_y);
      float c_s = (1.0 - alpha) * confidence_capped(y_s.confidence, cap);
      float m_s = mis_balance_terms(c_s * y_s.p_hat / jacobian, c_star * p_y, c_b * from);
      if (gris_stream_path(st, m_s * p_y * y_s.ucw * jacobian, p_y, f_y, 0.0, s + 2u, rng_next_float(rng))) {
        out_r = y_s;
        f = f_y;
      }
    }
  }
  // ML Table 1's coverage: a disoccluded front-layer pixel (domain_build.comp) that a splat from a
  // previous deep domain reached, or the deep backup's sample.
  bool deep_backup_in = backup_domain && bd.layer != 0u && bk.jacobian > 0.0;
  if (multilayer() && layer == 0u && (from_deep || deep_backup_in) && (b_domains[index].flags & DOMAIN_DISOCCLUDED) != 0u) {
    counter_add(COUNTER_DISOCCLUDED_COVERED, 1u);
    if (from_deep) counter_add(COUNTER_DISOCCLUDED_SPLATTED, 1u);
    if (deep_backup_in) counter_add(COUNTER_DISOCCLUDED_BACKUP, 1u);
    atomicOr(b_domains[index].flags, DOMAIN_COVERED);  // the domain map's "covered" (render/restir/domain_map.cpp)
  }
  if (st.selected != 0u && st.selected != GRIS_NONE) counter_add(COUNTER_TEMPORAL_SELECTED, 1u);
  if (st.selected == 1u) counter_add(COUNTER_SPLAT_BACKUP_SELECTED, 1u);
  if (last == first && layer == 0u) counter_add(COUNTER_TEMPORAL_NO_HISTORY, 1u);  // a hole: no splat landed here
  counter_add(COUNTER_SPLATS_LANDED, last - first);
  counter_max(COUNTER_SPLATS_MAX, last - first);
  // 5. Finalise, with the confidence of RS-main Eq. 17 (with the backup, its confidence is added too).
  float c_backup = backup_domain ? confidence_capped(xb.confidence, cap) : 0.0;
  finalise_reservoir(index, st, out_r, f, min(c_star + bp.confidence + c_backup, cap));
}
