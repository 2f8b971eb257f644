// The camera of a frame at a shutter time, and its primary rays (render space). Shared by `pt` and
// the ReSTIR passes so that both see exactly the same camera. Needs u_frame (GpuFrameConstants) and
// sampling/warp.h.
#ifndef STRATA_CAMERA_GLSL
#define STRATA_CAMERA_GLSL

#include "include/shutter.h"

// The thin lens's point for lens sample `lens` in [0,1)^2, relative to the lens centre (concentric
// disk of the aperture radius in the image plane's axes); 0 for a pinhole.
vec3 lens_offset(GpuCamera cam, vec2 lens) {
  if (!(cam.lens.x > 0.0)) return vec3(0.0);
  vec2 disk = sample_concentric_disk(lens) * cam.lens.x;
  return disk.x * normalize(cam.right.xyz) + disk.y * normalize(cam.up.xyz);
}

// The lens vertex of a lens sample (render space); the camera position for a pinhole.
vec3 lens_point(GpuCamera cam, vec2 lens) { return cam.position.xyz + lens_offset(cam, lens); }

// Camera ray through the subpixel position pixel + jitter of camera `cam` (box filter), with the
// thin lens when the camera has an aperture; in render space.
void primary_ray(GpuCamera cam, vec2 pixel, vec2 jitter, vec2 lens, out vec3 origin, out vec3 dir) {
  vec2 ndc = vec2((pixel.x + jitter.x) / float(u_frame.width) * 2.0 - 1.0, 1.0 - (pixel.y + jitter.y) / float(u_frame.height) * 2.0);
  vec3 d = cam.forward.xyz + ndc.x * cam.right.xyz + ndc.y * cam.up.xyz;
  origin = cam.position.xyz;
  if (cam.lens.x > 0.0) {
    vec3 focus_point = d * cam.lens.y;
    vec3 offset = lens_offset(cam, lens);
    origin += offset;
    dir = normalize(focus_point - offset);
  } else {
    dir = normalize(d);
  }
}

// The pinhole projection of render-space point p by camera `cam` at the origin (a frame's camera at
// its instant): x and y in [-1, 1] inside the image (right, up), z the depth along the view
// direction (x and y are meaningless unless z > 0). Backprojection into the previous frame.
vec3 camera_ndc(GpuCamera cam, vec3 p) {
  float z = dot(p, cam.forward.xyz);
  float x = dot(p, cam.right.xyz) / (z * dot(cam.right.xyz, cam.right.xyz));
  float y = dot(p, cam.up.xyz) / (z * dot(cam.up.xyz, cam.up.xyz));
  return vec3(x, y, z);
}

// The frame's camera at its instant (where its shutter closes).
GpuCamera camera_in(bool prev) {
  if (prev) return u_frame.prev_camera;  // (if, not ?: — see instance_in in scene_bridge.glsl)
  return u_frame.camera;
}

GpuShutter shutter_in(bool prev) {
  if (prev) return u_frame.prev_shutter;
  return u_frame.shutter;
}

bool motion_blur_in(bool prev) { return shutter_in(prev).open_position.w > 0.0; }

// The camera at shutter time `time` in [0, 1) of the current or previous frame (GpuShutter in
// frame_data.h; include/shutter.h): the frame's camera when its shutter does not move it.
GpuCamera camera_at(bool prev, float time) { return shutter_camera(camera_in(prev), shutter_in(prev), time); }

#endif
