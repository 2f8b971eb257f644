#version 460
// Pass `ray_throughput` (benchmark only): raw ray-query speed without shading. Each invocation
// traces `sample_count` camera rays (closest hit, coherent) and, from each primary hit, one
// cosine-distributed secondary ray (closest hit, incoherent). Counts rays and hits.
#extension GL_EXT_ray_query : require
#extension GL_GOOGLE_include_directive : require

layout(local_size_x = 8, local_size_y = 8, local_size_z = 1) in;

#include "include/bindings.h"
#include "include/frame_data.h"
#include "include/scene_bridge.glsl"
#include "sampling/rng.h"
#include "sampling/warp.h"

layout(push_constant) uniform Dispatch { GpuDispatchConstants u_dispatch; };
layout(set = 0, binding = BINDING_COUNTERS, std430) buffer Counters { uint b_counters[]; };

// Counter slots used by this pass (the path tracer's slots are not used at the same time).
const uint SLOT_PRIMARY_RAYS = 0u;
const uint SLOT_SECONDARY_RAYS = 1u;
const uint SLOT_HITS = 2u;

void main() {
  uvec2 pixel = gl_GlobalInvocationID.xy;
  if (pixel.x >= u_frame.width || pixel.y >= u_frame.height) return;
  uint index = pixel.y * u_frame.width + pixel.x;
  uint primary = 0u, secondary = 0u, hits = 0u;
  GpuCamera cam = u_frame.camera;
  for (uint s = 0u; s < u_dispatch.sample_count; ++s) {
    Rng rng = rng_init(index, u_dispatch.sample_base + s, u_frame.frame_index, u_frame.seed);
    vec2 j = rng_next_float2(rng);
    vec2 ndc = vec2((float(pixel.x) + j.x) / float(u_frame.width) * 2.0 - 1.0,
                    1.0 - (float(pixel.y) + j.y) / float(u_frame.height) * 2.0);
    vec3 dir = normalize(cam.forward.xyz + ndc.x * cam.right.xyz + ndc.y * cam.up.xyz);
    RayHit h;
    primary++;
    if (!trace_closest(vec3(0.0), dir, RAY_UNBOUNDED, h)) continue;
    hits++;
    SurfaceHit sh = load_hit(h);
    vec3 ng = dot(sh.geo_normal, dir) < 0.0 ? sh.geo_normal : -sh.geo_normal;
    vec3 t;
    vec3 b;
    make_onb(ng, t, b);
    vec3 d2 = to_world(sample_cosine_hemisphere(rng_next_float2(rng)), t, b, ng);
    secondary++;
    if (trace_closest(offset_ray_origin(sh.position, ng), d2, RAY_UNBOUNDED, h)) hits++;
  }
  atomicAdd(b_counters[SLOT_PRIMARY_RAYS], primary);
  atomicAdd(b_counters[SLOT_SECONDARY_RAYS], secondary);
  atomicAdd(b_counters[SLOT_HITS], hits);
}
