#version 460
// Pass `disocclusion`: which pixels are disoccluded (the `disoccluded_pixels` statistic): the
// pixel-centre primary hit of frame t (the primary pass's visibility buffer) was not visible from
// the camera of frame t-1. The hit's surface point is moved with its object's previous transform
// (the surface resolver), projected with the previous camera and tested for visibility in the
// previous frame's TLAS. A hit whose object changed LoD level, or that falls outside the previous
// image, is disoccluded too; a pixel that sees no surface is not. The evaluation restricts its
// error metrics to these pixels (ML footnote 3).
#extension GL_EXT_ray_query : require
#extension GL_GOOGLE_include_directive : require

layout(local_size_x = 8, local_size_y = 8, local_size_z = 1) in;

#include "include/bindings.h"
#include "include/frame_data.h"
#define STRATA_HISTORY 1
#include "include/scene_bridge.glsl"

layout(set = 0, binding = BINDING_DISOCCLUSION, std430) writeonly buffer Mask { uint b_mask[]; };
layout(set = 0, binding = BINDING_PRIMARY, std430) readonly buffer Primary { GpuPrimaryHit b_primary[]; };

#include "sampling/warp.h"
#include "include/camera.glsl"

// Relative distance by which an occluder must be in front of the point (the point's own surface,
// hit at the same distance up to float error, is not an occluder).
const float k_occluder_margin = 1e-3;

void main() {
  uvec2 pixel = gl_GlobalInvocationID.xy;
  if (pixel.x >= u_frame.width || pixel.y >= u_frame.height) return;
  uint index = pixel.y * u_frame.width + pixel.x;
  uint disoccluded = 0u;
  SurfacePoint centre = primary_surface(b_primary[index]);  // the primary pass's pixel-centre hit
  if (centre.instance != SURFACE_NONE) {
    ResolvedSurface before = resolve_surface(true, centre);
    // The point in frame t-1's render space (the previous camera at the origin).
    vec3 p = before.hit.position;
    vec3 ndc = camera_ndc(u_frame.prev_camera, p);
    float x = ndc.z > 0.0 ? ndc.x : 2.0;
    float y = ndc.z > 0.0 ? ndc.y : 2.0;
    float dist = length(p);
    if (before.reason != RESOLVE_OK || !(abs(x) <= 1.0 && abs(y) <= 1.0) || !(dist > 0.0)) {
      disoccluded = 1u;  // another LoD level, or outside the previous image
    } else {
      RayHit h;
      bool hit = trace_closest_in(true, vec3(0.0), p / dist, dist * (1.0 + k_occluder_margin), h);
      if (hit && h.t < dist * (1.0 - k_occluder_margin)) disoccluded = 1u;
    }
  }
  b_mask[index] = disoccluded;
}
