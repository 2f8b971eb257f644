#version 460
// Pass `ray_probe`: traces an explicit list of rays and returns each closest hit as the ray query
// reports it (instance, primitive, triangle, barycentrics, t). Used to check the acceleration
// structures against a CPU intersector and, by the service, to pick objects under a pixel; with
// PROBE_SPEC_PREVIOUS it traces the previous frame's slot (tests of the scene history).
#extension GL_EXT_ray_query : require
#extension GL_GOOGLE_include_directive : require

layout(local_size_x = 64, local_size_y = 1, local_size_z = 1) in;

#include "include/bindings.h"
#include "include/probe_data.h"
#define STRATA_HISTORY  // u_tlas_prev, b_instances_prev; a scene without history binds its one slot there
#include "include/scene_bridge.glsl"

layout(constant_id = PROBE_SPEC_PREVIOUS) const bool k_previous = false;

layout(push_constant) uniform Dispatch { GpuDispatchConstants u_dispatch; };
layout(set = 0, binding = BINDING_PROBE_RAYS, std430) readonly buffer Rays { GpuProbeRay b_rays[]; };
layout(set = 0, binding = BINDING_PROBE_HITS, std430) writeonly buffer Hits { GpuProbeHit b_hits[]; };

void main() {
  uint i = gl_GlobalInvocationID.x;
  if (i >= u_dispatch.sample_count) return;
  GpuProbeRay r = b_rays[i];
  RayHit h;
  GpuProbeHit out_hit;
  out_hit.t = -1.0;
  out_hit.instance = 0u;
  out_hit.geometry = 0u;
  out_hit.triangle = 0u;
  out_hit.bary = vec2(0.0);
  out_hit.lod = 0u;
  out_hit.pad = 0u;
  if (trace_span(k_previous, r.origin_tmin.xyz, r.origin_tmin.w, r.dir_tmax.xyz, r.dir_tmax.w, false, h)) {
    out_hit.t = h.t;
    out_hit.instance = h.instance;
    out_hit.geometry = h.geometry;
    out_hit.triangle = h.triangle;
    out_hit.bary = h.bary;
    out_hit.lod = instance_in(k_previous, h.instance).lod;
  }
  b_hits[i] = out_hit;
}
