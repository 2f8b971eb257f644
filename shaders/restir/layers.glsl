// Pixel-layer domains in the passes (restir-multilayer; restir/layer_data.h, docs/ARCHITECTURE.md,
// "Pixel layers"). Include after the scene bridge and restir/restir_pass.glsl.
//
// Which domain a primary vertex x (camera distance d from the sample's lens point x_0) belongs to in
// pixel p: the front layer when the camera ray sees it (ML Eq. 3, A_1); otherwise the active deep
// domain (p, i) whose depth range D_i holds d, when x is the first hit from x_0 + L_i r (ML Eq. 4;
// the restricted query, Fig. 3); otherwise none. The test reads geometry only, and a splat's and
// its reverse splat's layers come from the same rule in their frames, so the forward and reverse
// maps stay inverse to each other (RS-main Eq. 11, 13).
#ifndef STRATA_LAYERS_GLSL
#define STRATA_LAYERS_GLSL

#include "restir/layer_data.h"

layout(set = 0, binding = BINDING_DOMAINS, std430) buffer Domains { GpuDomainRange b_domains[]; };
#ifdef STRATA_HISTORY
layout(set = 0, binding = BINDING_DOMAINS_PREV, std430) readonly buffer DomainsPrev { GpuDomainRange b_domains_prev[]; };
#endif

// A hit this much nearer than x (relative to x's distance) hides x; closer than that it is x's own
// surface found at float precision.
const float LAYER_OCCLUDER_MARGIN = 1e-3;

bool multilayer() { return u_restir.layers > 1u; }

GpuDomainRange domain_range_in(bool prev, uint d) {
#ifdef STRATA_HISTORY
  if (prev) return b_domains_prev[d];
#endif
  return b_domains[d];
}

uint domain_in(bool prev, uvec2 pixel, uint layer) { return prev ? prev_domain_of(pixel, layer) : domain_of(pixel, layer); }

// The active deep domain of `pixel` (in the current or previous frame) whose depth range holds the
// camera distance d, as its layer; 0 when there is none (ML Sec. 4.2: "we identify the depth
// range D_i that contains d(x, x_0)").
uint deep_layer_by_range(bool prev, uvec2 pixel, float d, out float range_min, out float range_max) {
  range_min = 0.0;
  range_max = 0.0;
  for (uint i = 1u; i < u_restir.layers; ++i) {
    GpuDomainRange r = domain_range_in(prev, domain_in(prev, pixel, i));
    if ((r.flags & DOMAIN_ACTIVE) != 0u && d >= r.range_min && d <= r.range_max) {
      range_min = r.range_min;
      range_max = r.range_max;
      return i;
    }
  }
  return 0u;
}

// The layer of `pixel`'s active domain whose depth range holds d, the front layer's included;
// LAYERS_MAX when none does. Reads ranges only (no ray): the confidence lookups of RS-main Eq. 17
// for a representative hit moved back to the previous frame.
uint layer_by_range(bool prev, uvec2 pixel, float d) {
  for (uint i = 0u; i < u_restir.layers; ++i) {
    GpuDomainRange r = domain_range_in(prev, domain_in(prev, pixel, i));
    if ((r.flags & DOMAIN_ACTIVE) != 0u && d >= r.range_min && d <= r.range_max) return i;
  }
  return LAYERS_MAX;
}

// Whether a primary ray that found a surface at primary_t (0: none) hides a point at distance d.
bool hidden_at(float primary_t, float d) { return primary_t > 0.0 && primary_t < d * (1.0 - LAYER_OCCLUDER_MARGIN); }

// Where a walk along a ray continues after a hit at distance t: just beyond it.
float step_beyond(float t) { return t + max(t * 1e-4, 1e-5); }

#endif
