#version 460
// Pass `temporal` (its first dispatch; restir-gather and restir-di with the unbiased MIS): the
// reverse shift of the two-domain generalized balance heuristic (RS-main Eq. 6/7). Each pixel finds
// the history pixel q exactly as restir_temporal.comp does (restir/temporal_history.glsl: the same
// visibility buffers, so the same q), shifts its canonical sample back into q in frame t-1 (the
// previous TLAS, transforms, camera and light totals) and writes p-hat from q,
//   p-hat_q(T^-1(y_c)) |dT^-1/dy_c|  (RS-main Eq. 7),
// to BINDING_TEMPORAL_FROM_Q (0 where there is no history, no canonical sample or the shift fails),
// which restir_temporal.comp reads for the canonical sample's MIS weight. A pass of its own: a shift
// that may run in either frame is compiled for both, about 60 s of LLVM on lavapipe against 27 s
// for each frame's alone, and the two passes compile in parallel.
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
layout(set = 0, binding = BINDING_TEMPORAL_FROM_Q, std430) writeonly buffer FromQ { float b_from_q[]; };

#include "restir/temporal_history.glsl"

void main() {
  uvec2 pixel = gl_GlobalInvocationID.xy;
  if (pixel.x >= u_frame.width || pixel.y >= u_frame.height) return;
  float from_q = 0.0;
  Reservoir canonical = unpack_reservoir(b_out[domain_of(pixel, 0u)]);

  // 1. Find the history (its LoD mappings are counted by restir_temporal.comp).
  Backprojection bp;
  if (reservoir_valid(canonical) && find_temporal_neighbor(pixel, true, false, bp)) {
    uvec2 q = bp.q;
    // 2. Shift the canonical sample into q (frame t-1), where q's reservoir takes part (its confidence).
    if (unpack_reservoir(b_in[prev_domain_of(q, 0u)]).confidence > 0.0) {
      bool moved = (u_frame.history_flags & HISTORY_SCENE_MOVED) != 0u;
      uint entry = q.y * u_frame.prev_width + q.x;
      ShiftResult s = shift_path(true, vec2(q), domain_primary(b_primary_prev[entry], entry), canonical.y, moved);
      count_shift(s);
      if (s.reason == SHIFT_OK) from_q = p_hat_from(luminance(s.f), s.jacobian);
    }
  }
  b_from_q[pixel_index(pixel)] = from_q;
  counter_add(COUNTER_RAYS_TEMPORAL, g_rays);
}
