#version 460
// Pass `splat_project` (restir-splat; RS-supp 3.1 steps 1 and 3 of the counting sort, with the
// shifts computed here): every previous pixel i's reservoir X_i is splatted forward into the current
// frame (RS-main 4.1.1: primary hit kept in object space, projected through the new camera, visible
// from the new lens vertex, suffix by the hybrid shift), and counted in the current pixel it lands
// in. The record keeps what the resampling weights of RS-main Eq. 10-11 need. Over an open shutter
// (motion blur) a thread per previous pixel and time time_partition n (gl_GlobalInvocationID.z) splats
// into time_partition n (multi-splatting, RS-main Eq. 19); records and targets are per (n, i).
// restir-multilayer (ML 4.1, 4.2): every active previous domain (pixel, layer) splats, the front
// layer's in the image dispatch and the deep ones in a dispatch over the previous frame's compacted
// list (SPEC_DOMAIN_LIST; each thread splats its domain into every time partition); a sample whose primary hit is hidden now
// lands in the deeper domain whose depth range holds it (restir/layers.glsl), or nowhere.
#extension GL_EXT_ray_query : require
#extension GL_GOOGLE_include_directive : require

layout(local_size_x = 8, local_size_y = 8, local_size_z = 1) in;

#define STRATA_HISTORY 1
#include "include/scene_bridge.glsl"
#include "restir/restir_pass.glsl"
#include "restir/splat.glsl"
#include "restir/splat_data.h"
#include "restir/domain_list_prev.glsl"

layout(set = 0, binding = BINDING_RESERVOIRS_IN, std430) readonly buffer ReservoirsIn { PackedReservoir b_in[]; };
layout(set = 0, binding = BINDING_SPLATS, std430) writeonly buffer Splats { SplatRecord b_splats[]; };
layout(set = 0, binding = BINDING_SPLAT_TARGET, std430) writeonly buffer Targets { uint b_target[]; };
layout(set = 0, binding = BINDING_SPLAT_COUNT, std430) buffer Counts { uint b_count[]; };

// Splats previous domain i into time partition `time_partition`.
void splat(uint i, uint time_partition) {
  uint record = time_partition * prev_domain_count() + i;  // records: per partition, per previous domain
  // b_target[record] stays SPLAT_NONE (filled before the pass) unless the splat lands.
  Reservoir x = unpack_reservoir(b_in[i]);  // an inactive deep domain holds none (domain_fill.comp)
  if (!reservoir_valid(x)) return;
  bool moved = (u_frame.history_flags & HISTORY_SCENE_MOVED) != 0u;
  ShiftJob job = splat_prepare(false, x.y, time_partition);
  // The front layer, then (restir-multilayer) the deeper domain whose depth range holds the hidden
  // primary hit (ML Fig. 3): one shift_path call site.
  ShiftResult r = shift_none(SHIFT_FAIL_ZERO);
  float jacobian = 0.0;
  bool hidden = false;
  for (uint attempt = 0u; attempt < 2u; ++attempt) {
    if (attempt == 1u) {
      hidden = r.reason == SHIFT_FAIL_PRIMARY && hidden_at(r.primary_t, job.distance);
      if (!splat_deeper(job, r)) break;
      counter_add(COUNTER_TEMPORAL_FAIL + r.reason, 1u);  // the front-layer attempt
      counter_add(k_layer_stepping ? COUNTER_SPLAT_STEP_RAYS : COUNTER_SPLAT_RANGE_RAYS, 1u);  // the query after the layer test
    }
    r = run_shift(job, moved);
    jacobian = shift_finish(job, r);
    counter_add(COUNTER_TEMPORAL_SHIFTS, 1u);
    counter_add(COUNTER_RAYS_TEMPORAL, r.rays);
    count_suffix(r, COUNTER_RAYS_REPLAY);
    if (r.reason == SHIFT_OK) break;
  }
  if (r.reason != SHIFT_OK) {
    counter_add(COUNTER_TEMPORAL_FAIL + r.reason, 1u);
    if (!job.ok && r.reason == SHIFT_FAIL_PRIMARY) counter_add(COUNTER_SPLATS_OFFSCREEN, 1u);
    if (job.ok && job.layer == 0u && r.reason == SHIFT_FAIL_PRIMARY) counter_add(COUNTER_SPLATS_OCCLUDED, 1u);
    if (multilayer() && hidden && job.layer == 0u) counter_add(COUNTER_SPLATS_NO_LAYER, 1u);
    return;
  }
  if (job.layer != 0u) counter_add(COUNTER_SPLATS_DEEP, 1u);
  Reservoir y = x;  // W, confidence and p-hat_prev of X_i; the sample becomes Y_i
  y.y = shifted_sample(x.y, r);
  y.y.jitter = job.y.jitter;
  y.y.time = job.y.time;
  // X_i's confidence, capped where it lands (restir_splat_resample.comp) with the landing domain's cap.
  SplatRecord rec;
  rec.reservoir = pack_reservoir(y);
  rec.f_jacobian = vec4(r.f, jacobian);
  b_splats[record] = rec;
  uint j = domain_of(uvec2(job.pixel), job.layer);  // the splat's key: the domain it landed in
  b_target[record] = j;
  atomicAdd(b_count[j], 1u);
}

void main() {
  uint i;
  uint first_partition = 0u;
  uint end_partition = splat_partitions();
  if (k_domain_list) {
    if (!prev_list_entry(i)) return;
  } else {
    uvec2 prev_pixel = gl_GlobalInvocationID.xy;  // z: the time partition
    if (prev_pixel.x >= u_frame.prev_width || prev_pixel.y >= u_frame.prev_height || gl_GlobalInvocationID.z >= end_partition) return;
    i = prev_domain_of(prev_pixel, 0u);
    first_partition = gl_GlobalInvocationID.z;
    end_partition = first_partition + 1u;
  }
  for (uint n = first_partition; n < end_partition; ++n) splat(i, n);  // one call site: lavapipe inlines a traversal per site
}
