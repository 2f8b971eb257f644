// The thin-lens projection of a point into an image (RS-main 4.1.1, 4.5): where a splat lands, where
// a representative hit propagates to (domain_propagate.comp). Needs GpuCamera (include/frame_data.h).
#ifndef STRATA_PROJECTION_GLSL
#define STRATA_PROJECTION_GLSL

// Projects p through the thin lens from lens point o to the image (pixel + subpixel); false when it
// falls outside. For a pinhole (o = the camera position) this is the perspective projection.
bool project(GpuCamera cam, uint w, uint h, vec3 p, vec3 o, out uvec2 pixel, out vec2 jitter) {
  vec3 fwd = cam.forward.xyz;
  vec3 e = p - o;
  float along = dot(fwd, e);
  if (!(along > 0.0)) return false;
  float focus = cam.lens.x > 0.0 ? cam.lens.y : 1.0;
  vec3 c = cam.position.xyz;
  vec3 d = (o - c + e * ((focus - dot(fwd, o - c)) / along)) / focus;  // relative to c, on the plane forward . d = 1
  float x = dot(d, cam.right.xyz) / dot(cam.right.xyz, cam.right.xyz);
  float y = dot(d, cam.up.xyz) / dot(cam.up.xyz, cam.up.xyz);
  vec2 s = vec2((x + 1.0) * 0.5 * float(w), (1.0 - y) * 0.5 * float(h));
  if (!(s.x >= 0.0 && s.y >= 0.0 && s.x < float(w) && s.y < float(h))) return false;
  pixel = uvec2(s);
  jitter = clamp(s - vec2(pixel), vec2(0.0), vec2(0.99999994));
  return true;
}

#endif
