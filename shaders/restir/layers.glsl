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

// layer_mode uniform and no-depth-ranges: a deep domain is A_i = {x | rank(x) = i} (ML Eq. 3) and a
// splat finds its layer by walking the camera ray (ML Fig. 2) instead of one restricted query.
layout(constant_id = SPEC_LAYER_STEPPING) const bool k_layer_stepping = false;

// A hit this much nearer than x (relative to x's distance) hides x; closer than that it is x's own
// surface found at float precision.
const float LAYER_OCCLUDER_MARGIN = 1e-3;

bool multilayer() { return restir_layers() > 1u; }

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
  for (uint i = 1u; i < restir_layers(); ++i) {
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
  for (uint i = 0u; i < restir_layers(); ++i) {
    GpuDomainRange r = domain_range_in(prev, domain_in(prev, pixel, i));
    if ((r.flags & DOMAIN_ACTIVE) != 0u && d >= r.range_min && d <= r.range_max) return i;
  }
  return LAYERS_MAX;
}

// Whether a primary ray that found a surface at primary_t (0: none) hides a point at distance d.
bool hidden_at(float primary_t, float d) { return primary_t > 0.0 && primary_t < d * (1.0 - LAYER_OCCLUDER_MARGIN); }

// Where a walk along a ray continues after a hit at distance t: just beyond it.
float step_beyond(float t) { return t + max(t * 1e-4, 1e-5); }

// Layers by rank (the ML paper's original A_i = {x | rank(x) = i}, Eq. 3; layer_mode uniform and
// no-depth-ranges, and the propagation of representative hits): the ray from `origin` along `dir`
// is walked through its surfaces with closest-hit queries (ML Fig. 2). The first surface is layer
// 0, every front face behind it one layer deeper (restir/layer_data.h).
struct LayerWalk {
  uint layer;     // the target's layer; LAYERS_MAX when the walk did not reach it (or it is deeper than the k layers)
  uint occluder;  // the instance of the layer in front of it (OCCLUDER_NONE for layer 0)
  float t_start;  // where a query that must find the target first may start: just beyond the surface before it
  uint rays;
};

bool same_triangle(RayHit h, SurfacePoint p) { return h.instance == p.instance && h.geometry == p.geometry && h.triangle == p.triangle; }

// The layer of the point `target` at distance `dist` along the ray, in the current or previous frame.
// The target is recognised by its triangle, or by its instance at its distance (a neighbouring
// triangle of the same surface found at float precision).
LayerWalk walk_to_point(bool prev, vec3 origin, vec3 dir, SurfacePoint target, float dist) {
  LayerWalk w;
  w.layer = LAYERS_MAX;
  w.occluder = OCCLUDER_NONE;
  w.t_start = 0.0;
  w.rays = 0u;
  uint behind = 0u;  // front faces met after the first surface
  float t0 = 0.0;
  for (uint step = 0u; step < 2u * LAYERS_MAX + 2u; ++step) {
    RayHit h;
    w.rays++;
    if (!trace_closest_in(prev, origin + dir * t0, dir, RAY_UNBOUNDED, h)) break;
    float t = t0 + h.t;
    if (same_triangle(h, target) || (h.instance == target.instance && abs(t - dist) <= dist * LAYER_OCCLUDER_MARGIN)) {
      w.layer = step == 0u ? 0u : behind + 1u;
      w.t_start = t0;
      break;
    }
    if (t > dist * (1.0 + LAYER_OCCLUDER_MARGIN)) break;  // passed it: the target is not on this ray
    if (step == 0u) {
      w.occluder = h.instance;
    } else if (dot(load_hit_in(prev, h).geo_normal, dir) < 0.0) {
      behind++;
      w.occluder = h.instance;
      if (behind + 1u >= restir_layers()) break;  // deeper than the k layers
    }
    t0 = step_beyond(t);
  }
  return w;
}

// The surface of layer `layer` >= 1 along the ray, as `hit` with t from `origin` (a deep domain's
// primary vertex by rank); false when the ray has fewer layers.
bool walk_to_layer(vec3 origin, vec3 dir, uint layer, out RayHit hit, inout uint rays) {
  uint behind = 0u;  // front faces met after the first surface
  float t0 = 0.0;
  for (uint step = 0u; step < 2u * LAYERS_MAX + 2u; ++step) {
    rays++;
    if (!trace_closest(origin + dir * t0, dir, RAY_UNBOUNDED, hit)) return false;
    hit.t += t0;
    if (step > 0u && dot(load_hit(hit).geo_normal, dir) < 0.0 && ++behind == layer) return true;
    t0 = step_beyond(hit.t);
  }
  return false;
}

#endif
