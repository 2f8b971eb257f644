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

float prev_confidence(ivec2 q) {
  if (q.x < 0 || q.y < 0 || q.x >= int(u_frame.prev_width) || q.y >= int(u_frame.prev_height)) return 0.0;
  return confidence_capped(unpack_reservoir(b_in[uint(q.y) * u_frame.prev_width + uint(q.x)]).confidence, u_restir.confidence_cap);
}

// RS-main 4.3: the previous confidences bilinearly interpolated at the backprojection of this
// pixel's centre (its primary hit moved back with its object's previous transform); 0 when the
// centre sees nothing, changed LoD level, or falls outside the previous image.
float backprojected_confidence(uvec2 pixel) {
  vec3 origin;
  vec3 dir;
  primary_ray(u_frame.camera, vec2(pixel), vec2(0.5), vec2(0.5), origin, dir);
  RayHit h;
  if (!trace_closest(origin, dir, 1e30, h)) return 0.0;
  GpuInstance before = instance_in(true, h.instance);
  if (before.lod != b_instances[h.instance].lod) return 0.0;
  vec3 p = load_hit_with(before, h).position;
  uvec2 q;
  vec2 sub;
  if (!project(u_frame.prev_camera, u_frame.prev_width, u_frame.prev_height, p, vec3(0.0), q, sub)) return 0.0;
  vec2 s = vec2(q) + sub - 0.5;  // continuous coordinates of pixel centres
  ivec2 b = ivec2(floor(s));
  vec2 t = s - vec2(b);
  return (1.0 - t.x) * (1.0 - t.y) * prev_confidence(b) + t.x * (1.0 - t.y) * prev_confidence(b + ivec2(1, 0)) +
         (1.0 - t.x) * t.y * prev_confidence(b + ivec2(0, 1)) + t.x * t.y * prev_confidence(b + ivec2(1, 1));
}

void main() {
  uvec2 pixel = gl_GlobalInvocationID.xy;
  if (pixel.x >= u_frame.width || pixel.y >= u_frame.height) return;
  uint index = pixel_index(pixel);
  Reservoir canonical = unpack_reservoir(b_out[index]);
  vec3 f_canonical = b_contribution[index].rgb;
  float c_star = canonical.confidence;
  bool moved = (u_frame.history_flags & HISTORY_SCENE_MOVED) != 0u;

  // Reverse splat of the canonical sample (for Eq. 13).
  float from_r = 0.0;
  float c_r = 0.0;
  if (reservoir_valid(canonical)) {
    SplatResult back = splat_path(true, canonical.y, moved);
    atomicAdd(b_counters[COUNTER_TEMPORAL_SHIFTS], 1u);
    atomicAdd(b_counters[COUNTER_RAYS_TEMPORAL], back.shift.rays);
    if (back.shift.reason == SHIFT_OK) {
      from_r = p_hat_from(luminance(back.shift.f), back.jacobian);
      c_r = prev_confidence(ivec2(back.pixel));
    } else {
      atomicAdd(b_counters[COUNTER_TEMPORAL_FAIL + back.shift.reason], 1u);
    }
  }

  Rng rng = rng_init(index, 0x5B1A7u, u_frame.frame_index, u_frame.seed);
  GrisState st = gris_begin();
  float m_star = mis_balance2(c_star, canonical.p_hat, c_r, from_r);
  gris_stream(st, m_star * canonical.p_hat * canonical.ucw, canonical.p_hat, c_star, 0u, rng_next_float(rng));
  Reservoir out_r = canonical;
  vec3 f = f_canonical;
  uint first = b_offsets[index];
  uint last = b_offsets[index + 1u];
  for (uint s = first; s < last; ++s) {
    SplatRecord rec = b_splats[b_list[s]];
    Reservoir y = unpack_reservoir(rec.reservoir);
    vec3 f_y = rec.f_jacobian.xyz;
    float jacobian = rec.f_jacobian.w;
    float p_y = luminance(f_y);
    float from_i = y.p_hat / jacobian;                                 // p-hat_prev(X_i) |T'|^-1
    float m_i = mis_balance2(y.confidence, from_i, c_star, p_y);      // Eq. 11
    if (gris_stream(st, m_i * p_y * y.ucw * jacobian, p_y, 0.0, s + 1u, rng_next_float(rng))) {  // Eq. 10
      out_r = y;
      f = f_y;
    }
  }
  if (st.selected != 0u && st.selected != GRIS_NONE) atomicAdd(b_counters[COUNTER_TEMPORAL_SELECTED], 1u);
  if (last == first) atomicAdd(b_counters[COUNTER_TEMPORAL_NO_HISTORY], 1u);  // a hole: no splat landed here
  atomicAdd(b_counters[COUNTER_SPLATS_LANDED], last - first);
  atomicMax(b_counters[COUNTER_SPLATS_MAX], last - first);
  out_r.p_hat = st.selected_p_hat;
  out_r.ucw = gris_ucw(st);  // RS-main Eq. 5
  // RS-main Eq. 17.
  out_r.confidence = min(c_star + backprojected_confidence(pixel), u_restir.confidence_cap);
  if (st.selected == GRIS_NONE) {
    float c = out_r.confidence;
    out_r = reservoir_empty();
    out_r.confidence = c;
    f = vec3(0.0);
  }
  if (st.rejected > 0u) atomicAdd(b_counters[COUNTER_NONFINITE_REJECTED], st.rejected);
  store_output(index, out_r, f);
}
