// The camera at a shutter time (motion blur, RS-main 4.4; RS-supp 3.3.1), shared by the host (unit
// tests against scene/shutter.h) and the passes (include/camera.glsl).
#ifndef STRATA_SHUTTER_H
#define STRATA_SHUTTER_H
#include "include/frame_data.h"
#include "include/lang.h"

STRATA_NAMESPACE_BEGIN

// Rodrigues' rotation of v by `angle` about the unit `axis`.
INLINE vec3 rotate_about(vec3 v, vec3 axis, float angle) {
  float c = cos(angle);
  float s = sin(angle);
  return v * c + cross(axis, v) * s + axis * (dot(axis, v) * (1.0f - c));
}

// The camera at shutter time `time` in [0, 1) (0 = opening) of a frame whose camera at its instant
// is `close` and whose shutter is `sh` (GpuShutter): `close` itself when the shutter does not move it.
INLINE GpuCamera shutter_camera(GpuCamera close, GpuShutter sh, float time) {
  if (!(sh.open_position.w > 0.0f)) return close;
  GpuCamera cam = close;
  float back = 1.0f - time;  // fraction of the way back to the opening
  float angle = back * sh.rotation.w;
  vec3 axis = vec3(sh.rotation);
  float fov_scale = tan(0.5f * mix(sh.open_lens.x, sh.open_lens.w, time)) / tan(0.5f * sh.open_lens.w);
  cam.forward = vec4(rotate_about(vec3(close.forward), axis, angle), 0.0f);
  cam.right = vec4(rotate_about(vec3(close.right), axis, angle) * fov_scale, 0.0f);
  cam.up = vec4(rotate_about(vec3(close.up), axis, angle) * fov_scale, 0.0f);
  cam.lens = vec4(mix(sh.open_lens.y, close.lens.x, time), mix(sh.open_lens.z, close.lens.y, time), 0.0f, 0.0f);
  cam.position = vec4(vec3(sh.open_position) * back, 0.0f);
  return cam;
}

STRATA_NAMESPACE_END
#endif
