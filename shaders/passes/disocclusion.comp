#version 460
// Pass `disocclusion`: which pixels are disoccluded (DESIGN.md section 4, `disoccluded_pixels`):
// the pixel-centre primary hit of frame t was not visible from the camera of frame t-1. The hit's
// surface point is moved with its object's previous transform, projected with the previous camera
// and tested for visibility in the previous frame's TLAS. A hit whose object changed LoD level, or
// that falls outside the previous image, is disoccluded too; a pixel that sees no surface is not.
// Evaluation (issue 6, ML footnote 3) restricts its error metrics to these pixels.
#extension GL_EXT_ray_query : require
#extension GL_GOOGLE_include_directive : require

layout(local_size_x = 8, local_size_y = 8, local_size_z = 1) in;

#include "include/bindings.h"
#include "include/frame_data.h"
#define STRATA_HISTORY 1
#include "include/scene_bridge.glsl"

layout(set = 0, binding = BINDING_FRAME, std140) uniform Frame { GpuFrameConstants u_frame; };
layout(set = 0, binding = BINDING_DISOCCLUSION, std430) writeonly buffer Mask { uint b_mask[]; };

// Relative distance by which an occluder must be in front of the point (the point's own surface,
// hit at the same distance up to float error, is not an occluder).
const float k_occluder_margin = 1e-3;

vec3 centre_direction(GpuCamera cam, uvec2 pixel) {
  vec2 ndc = vec2((float(pixel.x) + 0.5) / float(u_frame.width) * 2.0 - 1.0, 1.0 - (float(pixel.y) + 0.5) / float(u_frame.height) * 2.0);
  return normalize(cam.forward.xyz + ndc.x * cam.right.xyz + ndc.y * cam.up.xyz);
}

void main() {
  uvec2 pixel = gl_GlobalInvocationID.xy;
  if (pixel.x >= u_frame.width || pixel.y >= u_frame.height) return;
  uint index = pixel.y * u_frame.width + pixel.x;
  uint disoccluded = 0u;
  vec3 to_point = vec3(0.0);
  float dist = 0.0;
  // Job 0 traces the current centre ray, job 1 the previous camera's ray to the moved point: one
  // call site (lavapipe inlines a traversal per call site).
  for (uint job = 0u; job < 2u; ++job) {
    bool prev = job == 1u;
    vec3 dir = prev ? to_point / dist : centre_direction(u_frame.camera, pixel);
    float t_max = prev ? dist * (1.0 + k_occluder_margin) : 1e30;
    RayHit h;
    bool hit = trace_closest_in(prev, vec3(0.0), dir, t_max, h);
    if (prev) {
      if (hit && h.t < dist * (1.0 - k_occluder_margin)) disoccluded = 1u;
      break;
    }
    if (!hit) break;
    GpuInstance before = instance_in(true, h.instance);
    if (before.lod != b_instances[h.instance].lod) {
      disoccluded = 1u;
      break;
    }
    // The point in frame t-1's render space (the previous camera at the origin).
    vec3 p = load_hit_with(before, h).position;
    GpuCamera cam = u_frame.prev_camera;
    float z = dot(p, cam.forward.xyz);
    float x = z > 0.0 ? dot(p, cam.right.xyz) / (z * dot(cam.right.xyz, cam.right.xyz)) : 2.0;
    float y = z > 0.0 ? dot(p, cam.up.xyz) / (z * dot(cam.up.xyz, cam.up.xyz)) : 2.0;
    dist = length(p);
    if (!(abs(x) <= 1.0 && abs(y) <= 1.0) || !(dist > 0.0)) {
      disoccluded = 1u;
      break;
    }
    to_point = p;
  }
  b_mask[index] = disoccluded;
}
