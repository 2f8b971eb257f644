#version 460
// Pass `primary` (stage primary; docs/ARCHITECTURE.md): the visibility buffer. Per pixel, the ray
// through the pixel centre and the lens centre at the frame's instant, traced once; the temporal
// stages (gather backprojection, splatting's backup and confidence) and the disocclusion mask read
// its hit instead of tracing the same ray again.
#extension GL_EXT_ray_query : require
#extension GL_GOOGLE_include_directive : require

layout(local_size_x = 8, local_size_y = 8, local_size_z = 1) in;

#include "include/bindings.h"
#include "include/frame_data.h"
#include "include/scene_bridge.glsl"

layout(set = 0, binding = BINDING_FRAME, std140) uniform Frame { GpuFrameConstants u_frame; };
layout(set = 0, binding = BINDING_PRIMARY, std430) writeonly buffer Primary { GpuPrimaryHit b_primary[]; };

#include "sampling/warp.h"
#include "include/camera.glsl"

void main() {
  uvec2 pixel = gl_GlobalInvocationID.xy;
  if (pixel.x >= u_frame.width || pixel.y >= u_frame.height) return;
  vec3 origin;
  vec3 dir;
  primary_ray(u_frame.camera, vec2(pixel), vec2(0.5), vec2(0.5), origin, dir);
  RayHit h;
  GpuPrimaryHit p;
  p.t = 0.0;
  p.instance = 0u;
  p.geometry = 0u;
  p.triangle = 0u;
  p.bary = vec2(0.0);
  p.lod = 0u;
  p.flags = 0u;
  if (trace_closest(origin, dir, 1e30, h)) {
    p.t = h.t;
    p.instance = h.instance;
    p.geometry = h.geometry;
    p.triangle = h.triangle;
    p.bary = h.bary;
    p.lod = b_instances[h.instance].lod;
    p.flags = PRIMARY_HIT;
  }
  b_primary[pixel.y * u_frame.width + pixel.x] = p;
}
