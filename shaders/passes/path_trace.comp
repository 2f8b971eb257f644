#version 460
// Pass `path_trace`: the reference unidirectional path tracer (method `pt`). Box-filtered subpixel
// jitter, optional thin lens, optional motion blur (shutter time uniform over the shutter, the camera
// at that time: Eq. 9 of RS-main integrated by Monte Carlo), next-event estimation to emitters and the environment combined with
// BSDF sampling by the power heuristic (a punctual light, which BSDF sampling never finds, with
// weight 1: NEE is its only strategy), Russian roulette. Adds `sample_count` samples per
// pixel to the accumulation buffer (rgb sum, a = sample count).
#extension GL_EXT_ray_query : require
#extension GL_GOOGLE_include_directive : require

layout(local_size_x = 8, local_size_y = 8, local_size_z = 1) in;

#include "include/bindings.h"
#include "include/frame_data.h"
#include "include/scene_bridge.glsl"
#include "sampling/emitter_pdf.h"
#include "sampling/russian_roulette.h"
#include "material/bsdf.h"
#include "sampling/mis.h"
#include "sampling/rng.h"
#include "sampling/warp.h"

layout(constant_id = SPEC_THIN_LENS) const bool k_thin_lens = false;
layout(constant_id = SPEC_ENV_NEE) const bool k_env_nee = false;
layout(constant_id = SPEC_EMITTERS) const bool k_emitters = true;
layout(constant_id = SPEC_MOTION_BLUR) const bool k_motion_blur = false;

layout(push_constant) uniform Dispatch { GpuDispatchConstants u_dispatch; };
layout(set = 0, binding = BINDING_COUNTERS, std430) buffer Counters { uint b_counters[]; };
layout(set = 0, binding = BINDING_ACCUM, std430) buffer Accum { vec4 b_accum[]; };

#include "include/camera.glsl"


uint g_rays_primary = 0u;
uint g_rays_bounce = 0u;
uint g_rays_shadow = 0u;

// The thin lens keeps the pinhole ray's point on the focus plane sharp (Pharr et al., PBRT 5.2.3).
void camera_ray(vec2 pixel, inout Rng rng, out vec3 origin, out vec3 dir) {
  vec2 jitter = rng_next_float2(rng);  // box filter over the pixel
  vec2 lens = k_thin_lens ? rng_next_float2(rng) : vec2(0.5);
  GpuCamera cam = u_frame.camera;
  if (k_motion_blur) cam = camera_at(false, rng_next_float(rng));  // uniform over the shutter
  if (!k_thin_lens) cam.lens.x = 0.0;
  primary_ray(cam, pixel, jitter, lens, origin, dir);
}

vec3 trace_path(vec2 pixel, inout Rng rng) {
  vec3 origin;
  vec3 dir;
  camera_ray(pixel, rng, origin, dir);
  vec3 radiance = vec3(0.0);
  vec3 throughput = vec3(1.0);
  float prev_bsdf_pdf = 0.0;  // 0 marks the camera vertex: emission seen directly is not MIS-weighted
  vec3 prev_position = vec3(0.0);  // the surface point the ray left, where its NEE sampled lights
  vec4 prev_receiver = vec4(0.0);  // that surface as its NEE chose lights (bsdf_light_receiver)
  g_rays_primary++;

  for (uint depth = 1u; depth <= u_frame.max_depth; ++depth) {
    RayHit rh;
    if (!trace_closest(origin, dir, RAY_UNBOUNDED, rh)) {
      float w = 1.0;
      if (k_env_nee && prev_bsdf_pdf > 0.0) w = mis_power(prev_bsdf_pdf, environment_pdf(dir));
      radiance += throughput * environment_radiance(dir) * w;
      break;
    }
    SurfaceHit s = load_hit(rh);
    // The scene bridge's footprint rule: a ray cone at the primary vertex, the finest level past it.
    SurfaceMaterial m = material_at(s, depth == 1u ? primary_footprint(camera_spread(false), s.position, dot(s.geo_normal, dir)) : 0.0);
    bool double_sided = m.double_sided;
    float cos_hit = dot(s.geo_normal, -dir);
    bool front = cos_hit > 0.0;

    vec3 emission = m.emission;
    if (any(greaterThan(emission, vec3(0.0))) && (front || double_sided)) {
      float w = 1.0;
      if (k_emitters && prev_bsdf_pdf > 0.0) {
        float light_pdf = emitter_light_pdf(false, prev_position, prev_receiver, uvec3(rh.instance, rh.geometry, rh.triangle), m.light_emission,
                                            s.area, double_sided, rh.t, cos_hit);
        w = mis_power(prev_bsdf_pdf, light_pdf);
      }
      radiance += throughput * emission * w;
    }
    if (depth == u_frame.max_depth) break;

    // Shading frame on the side the ray arrived from (surfaces are two-sided for scattering).
    vec3 ng = front ? s.geo_normal : -s.geo_normal;
    vec3 ns = front ? s.shading_normal : -s.shading_normal;
    vec3 t;
    vec3 b;
    make_onb(ns, t, b);
    vec3 wo = to_local(-dir, t, b, ns);
    BsdfParams bsdf = m.bsdf;
    vec3 x = offset_ray_origin(s.position, ng);

    vec4 receiver = bsdf_light_receiver(ng, bsdf);  // this surface as light sampling weighs lights for it

    // Next-event estimation, MIS-weighted against BSDF sampling.
    if (k_emitters || k_env_nee || k_punctual) {
      LightSample ls;
      vec3 ul = vec3(rng_next_float2(rng), rng_next_float(rng));
      if (sample_light(s.position, receiver, ul, ls) && dot(ls.direction, ng) > 0.0) {
        vec3 wi = to_local(ls.direction, t, b, ns);
        vec3 f = bsdf_eval_cos(bsdf, wo, wi);
        if (any(greaterThan(f, vec3(0.0)))) {
          vec3 aim;
          float t_max;
          bool aimed = visibility_ray(x, s.position, ls.direction, ls.distance, aim, t_max);
          g_rays_shadow++;
          if (aimed && trace_visible(x, aim, t_max)) {
            float w = k_punctual && ls.delta ? 1.0 : mis_power(ls.pdf, bsdf_pdf(bsdf, wo, wi));
            radiance += throughput * f * ls.radiance * (w / ls.pdf);
          }
        }
      }
    }

    vec3 wi_local;
    vec3 weight;
    float pdf;
    vec3 ub = vec3(rng_next_float2(rng), rng_next_float(rng));
    if (!bsdf_sample(bsdf, wo, ub, wi_local, weight, pdf)) break;
    dir = to_world(wi_local, t, b, ns);
    if (dot(dir, ng) <= 0.0) break;  // shading normal sent the ray through the surface
    throughput *= weight;
    prev_bsdf_pdf = pdf;
    prev_position = s.position;
    prev_receiver = receiver;
    origin = x;

    if (float(depth) >= RR_START_DEPTH) {
      float survive = rr_survival(throughput);
      if (rng_next_float(rng) >= survive) break;
      throughput /= survive;
    }
    g_rays_bounce++;
  }
  return radiance;
}

void main() {
  uvec2 pixel = gl_GlobalInvocationID.xy;
  if (pixel.x >= u_frame.width || pixel.y >= u_frame.height) return;
  uint index = pixel.y * u_frame.width + pixel.x;
  vec3 sum = vec3(0.0);
  uint rejected = 0u;
  for (uint s = 0u; s < u_dispatch.sample_count; ++s) {
    Rng rng = rng_init(index, u_dispatch.sample_base + s, u_frame.frame_index, u_frame.seed);
    vec3 l = trace_path(vec2(pixel), rng);
    // docs/ARCHITECTURE.md, Robustness: a non-finite or negative sample never reaches a pixel; it is counted.
    if (any(isnan(l)) || any(isinf(l)) || any(lessThan(l, vec3(0.0)))) {
      rejected++;
      continue;
    }
    sum += l;
  }
  b_accum[index] += vec4(sum, float(u_dispatch.sample_count));
  atomicAdd(b_counters[COUNTER_RAYS_PRIMARY], g_rays_primary);
  atomicAdd(b_counters[COUNTER_RAYS_BOUNCE], g_rays_bounce);
  atomicAdd(b_counters[COUNTER_RAYS_SHADOW], g_rays_shadow);
  atomicAdd(b_counters[COUNTER_PATHS], u_dispatch.sample_count);
  if (rejected > 0u) atomicAdd(b_counters[COUNTER_NONFINITE_REJECTED], rejected);
}
