#version 460
// Pass `domain_fill` (stage domain_init; ML 4.3, Sec. 5): hole filling and compaction.
//   - A deep domain with a representative hit that no propagation activated is active when a
//     propagating domain of its layer lies within hole_fill_radius pixels (ML: "we treat neighboring
//     domains within a fixed radius of the current active domains as active"; they sample but do not
//     propagate: DOMAIN_FILLED, without DOMAIN_PROPAGATES).
//   - The silhouette band (silhouette_band > 0; not in the ML paper): an active deep domain farther
//     than silhouette_band pixels from every silhouette of the front layer (DOMAIN_SILHOUETTE,
//     domain_build) cannot be uncovered in the next frames unless an edge moves that far: it is
//     dormant instead, its representative hit still propagates (DOMAIN_PROPAGATES, the list's other
//     end for domain_propagate) but it samples nothing, so it costs no path, splat or resampling.
//     A hole-filled one there is simply inactive. The test reads geometry only, as activation does.
//   - The reveal prediction (reveal_lookahead > 0; ours): a deep domain whose motion domain_build
//     predicted samples only when flagged DOMAIN_REVEALING (the front layer moves off it within
//     reveal_lookahead frames); otherwise it is dormant (or, hole-filled, inactive) as above. The
//     silhouette band then decides only for the domains without a prediction.
//   - Every active deep domain is appended to the dense list that the initial and resampling passes
//     dispatch indirectly, one thread per domain (ML Sec. 5's compaction); the list dispatch's
//     workgroup count grows with it.
//   - An inactive deep domain holds no sample: its reservoir is emptied with confidence 0, so that no
//     splat leaves it and it weighs nothing in a reverse splat's MIS weight next frame.
// Counts the active domains by layer and how deep ones were activated (ML Table 1).
#extension GL_GOOGLE_include_directive : require

layout(local_size_x = 8, local_size_y = 8, local_size_z = 1) in;

#include "include/bindings.h"
#include "include/frame_data.h"
#include "restir/domain.h"
#include "restir/layer_data.h"
#include "restir/reservoir.h"
#include "restir/restir_data.h"

layout(set = 0, binding = BINDING_FRAME, std140) uniform Frame { GpuFrameConstants u_frame; };
layout(set = 0, binding = BINDING_RESTIR, std140) uniform Restir { GpuRestirConstants u_restir; };
layout(set = 0, binding = BINDING_COUNTERS, std430) buffer Counters { uint b_counters[]; };
layout(set = 0, binding = BINDING_RESERVOIRS_OUT, std430) buffer ReservoirsOut { PackedReservoir b_out[]; };
layout(set = 0, binding = BINDING_DOMAINS, std430) buffer Domains { GpuDomainRange b_domains[]; };
layout(set = 0, binding = BINDING_DOMAIN_LIST, std430) writeonly buffer DomainList { uint b_domain_list[]; };
layout(set = 0, binding = BINDING_DOMAIN_ARGS, std430) buffer DomainArgs { GpuDomainArgs b_domain_args[2]; };

uint domain_at(uvec2 pixel, uint layer) { return domain_index(pixel, layer, u_frame.width, u_frame.height); }

// Whether a domain of `layer` within `radius` pixels of `pixel` (the pixel itself included) has
// `flag`. Hole filling asks for DOMAIN_PROPAGATES in the pixel's own layer (the pixel's own domain,
// when it propagates, is active already), the silhouette band for DOMAIN_SILHOUETTE in the front layer.
bool flag_within(uvec2 pixel, uint layer, uint radius, uint flag) {
  int r = int(radius);
  for (int dy = -r; dy <= r; ++dy)
    for (int dx = -r; dx <= r; ++dx) {
      ivec2 q = ivec2(pixel) + ivec2(dx, dy);
      if (dx * dx + dy * dy > r * r || q.x < 0 || q.y < 0 || q.x >= int(u_frame.width) || q.y >= int(u_frame.height)) continue;
      if ((b_domains[domain_at(uvec2(q), layer)].flags & flag) != 0u) return true;
    }
  return false;
}

// No sample (no SAMPLE_VALID, W = 0) and confidence 0: what no pass reads beyond reservoir_valid
// and the confidence.
PackedReservoir empty_reservoir() {
  PackedReservoir p;
  p.x1 = uvec4(0u);
  p.xk = uvec4(0u);
  p.radiance = uvec4(0u);
  p.weights = uvec4(0u);
  p.meta = uvec4(0u);
  p.shift = uvec4(0u);
  return p;
}

void main() {
  uvec2 pixel = gl_GlobalInvocationID.xy;
  if (pixel.x >= u_frame.width || pixel.y >= u_frame.height) return;
  if ((b_domains[domain_at(pixel, 0u)].flags & DOMAIN_ACTIVE) != 0u) atomicAdd(b_counters[COUNTER_DOMAINS_ACTIVE], 1u);
  int near = -1;  // a silhouette within the band, once asked
  for (uint i = 1u; i < u_restir.layers; ++i) {
    uint d = domain_at(pixel, i);
    uint flags = b_domains[d].flags;
    if ((flags & DOMAIN_HIT) != 0u && (flags & DOMAIN_ACTIVE) == 0u && u_restir.hole_fill_radius > 0u &&
        flag_within(pixel, i, u_restir.hole_fill_radius, DOMAIN_PROPAGATES)) {
      flags |= DOMAIN_ACTIVE | DOMAIN_FILLED;
      b_domains[d].flags = flags;
    }
    if ((flags & DOMAIN_ACTIVE) != 0u && (u_restir.silhouette_band > 0u || u_restir.reveal_lookahead > 0u)) {
      bool samples;
      if ((flags & DOMAIN_PREDICTED) != 0u) {
        samples = (flags & DOMAIN_REVEALING) != 0u;
      } else if (u_restir.silhouette_band == 0u) {
        samples = true;
      } else {
        if (near < 0) near = flag_within(pixel, 0u, u_restir.silhouette_band, DOMAIN_SILHOUETTE) ? 1 : 0;
        samples = near == 1;
      }
      if (!samples) {
        flags &= ~(DOMAIN_ACTIVE | DOMAIN_FILLED);
        if ((flags & DOMAIN_PROPAGATES) != 0u) {
          flags |= DOMAIN_DORMANT;
          atomicAdd(b_counters[COUNTER_DOMAINS_DORMANT], 1u);
          uint j = atomicAdd(b_domain_args[DOMAIN_ARGS_DORMANT].count, 1u);
          b_domain_list[dormant_list_slot(j, u_restir.layers, u_frame.width, u_frame.height)] = d;
          atomicMax(b_domain_args[DOMAIN_ARGS_DORMANT].groups_x, j / DOMAIN_LIST_GROUP + 1u);
        }
        b_domains[d].flags = flags;
      }
    }
    if ((flags & DOMAIN_ACTIVE) == 0u) {
      b_out[d] = empty_reservoir();
      continue;
    }
    atomicAdd(b_counters[COUNTER_DOMAINS_ACTIVE + i], 1u);
    atomicAdd(b_counters[(flags & DOMAIN_FILLED) != 0u ? COUNTER_DOMAINS_FILLED : COUNTER_DOMAINS_PROPAGATED], 1u);
    uint slot = atomicAdd(b_domain_args[DOMAIN_ARGS_ACTIVE].count, 1u);
    b_domain_list[slot] = d;
    atomicMax(b_domain_args[DOMAIN_ARGS_ACTIVE].groups_x, slot / DOMAIN_LIST_GROUP + 1u);
  }
}
