// Reservoir splatting's reprojection shift (RS-main 4.1.1, 4.1.3): a path keeps its primary hit x_1
// in object space (y_1 = M M_prev^-1 x_1, which loading x_1's surface point with the target frame's
// instance transform gives directly), is projected through the target frame's camera (pinhole or
// thin lens with the lens sample kept, RS-main 4.5) to the subpixel position u it lands on, must be
// visible from the lens vertex y_0 (the camera ray through u must hit x_1's triangle again), and its
// suffix is then shifted by the hybrid shift from there (path_space.glsl).
//
// Motion blur (RS-main 4.4): the camera is the one at the sample's shutter time in each frame
// (camera_at). Over an open shutter the current frame's shutter is split into K partitions and every
// previous sample splats once into each, at t(n) = (n + t_prev) / K (RS-main Eq. 19; K = 1 is Eq. 18,
// the time offset kept); the reverse splat of a current sample finds its time_partition n = floor(t K).
//
// Jacobian: the subpixel factor |du/dv| of RS-main Eq. 14-16 (restir/reprojection.h, with both
// frames' pixel areas so that a zoom or a resolution change is exact) times the hybrid shift's
// density(x) / density(y), times the time factor 1/K (|T_n-hat| = |T_n| / K, RS-main 4.4.3; K for
// the reverse splat).
#ifndef STRATA_SPLAT_GLSL
#define STRATA_SPLAT_GLSL

#include "restir/path_space.glsl"
#include "restir/layers.glsl"
#include "restir/projection.glsl"
#include "restir/reprojection.h"


// A shift of either kind, prepared so that the caller runs its single shift_path call: the gather
// shift (replay with the sample's own subpixel position in a given pixel; the backup of RS-main 4.2
// and its inverse) or the splat (the subpixel position where the sample's primary hit projects).
struct ShiftJob {
  bool splat;
  bool prev;           // target frame
  vec2 pixel;          // target pixel (a splat sets it)
  PathSample y;        // the sample to shift, with the subpixel position it will be replayed at
  bool ok;             // false: failed before tracing (reason in `reason`)
  uint reason;
  float camera_ratio;  // splat: |du/dv| of RS-main Eq. 14-16 (reprojection.h); gather: 1
  float time_ratio;    // splat: 1/K forward, K reverse (RS-main 4.4.3); gather: 1 (time kept)
  // Multi-layer splatting (restir/layers.glsl): the target domain's layer, the depth range its
  // primary ray is restricted to (0 and RAY_UNBOUNDED for the front layer), and x_1's camera distance.
  uint layer;
  float t_min;
  float t_max;
  float distance;
  vec3 ray_origin;     // the splat's camera ray in the target frame: the lens point
  vec3 ray_dir;        // towards y_1
};

// K: the time partitions of this frame's shutter (1 when the camera does not move over it), as the
// host computed it (render/frame_constants.h time_partitions) and dispatches the splat passes.
uint splat_partitions() { return time_partitions(); }

// Splat of sample y (of the other frame) into the current (prev = false) or previous frame:
// projection, and the camera part of the Jacobian. Forward, `time_partition` is the time time_partition n
// it splats into (RS-main Eq. 19); the reverse splat ignores it (the sample's time decides).
ShiftJob splat_prepare(bool prev, PathSample y, uint time_partition) {
  ShiftJob job;
  job.splat = true;
  job.prev = prev;
  job.pixel = vec2(0.0);
  job.y = y;
  job.ok = false;
  job.reason = SHIFT_FAIL_PRIMARY;
  job.camera_ratio = 0.0;
  job.layer = 0u;
  job.t_min = 0.0;
  job.t_max = RAY_UNBOUNDED;
  job.distance = 0.0;
  job.ray_origin = vec3(0.0);
  job.ray_dir = vec3(0.0, 0.0, 1.0);
  float k = float(splat_partitions());
  float time_to;
  if (!prev) {
    time_to = (float(time_partition) + y.time) / k;  // RS-main Eq. 19
    job.time_ratio = 1.0 / k;
  } else {
    float tk = y.time * k;
    time_to = clamp(tk - min(floor(tk), k - 1.0), 0.0, 0.99999994);  // the inverse of Eq. 19
    job.time_ratio = k;
  }
  // x_1 in the sample's own frame, at the level it was stored at: never mapped (LOD_VERTEX_NONE
  // folds tau's code away at this call site, one ray-query traversal less for lavapipe to compile).
  ResolvedSurface x1_from = resolve_surface_as(!prev, y.x1, LOD_VERTEX_NONE);
  ResolvedSurface y1_to = resolve_surface(prev, y.x1);      // y_1 = tau(x_1) in the target frame (LOD 4.4, "LoD-aware primary hit reprojection")
  count_lod_mapping(y1_to);
  if (x1_from.reason != RESOLVE_OK || y1_to.reason != RESOLVE_OK) {
    job.reason = SHIFT_FAIL_STALE;  // gone, or another LoD level that tau does not reach
    return job;
  }
  job.y.x1 = y1_to.point;  // the primary ray must find y_1's triangle at the target's level
  SurfaceHit from = x1_from.hit;
  SurfaceHit to = y1_to.hit;
  GpuCamera cam_from = camera_at(!prev, y.time);
  GpuCamera cam_to = camera_at(prev, time_to);
  uvec2 size_from = image_size(!prev);
  uvec2 size_to = image_size(prev);
  uint w_from = size_from.x;
  uint h_from = size_from.y;
  uint w_to = size_to.x;
  uint h_to = size_to.y;
  vec3 o_to = lens_point(cam_to, y.lens);
  uvec2 pixel;
  vec2 jitter;
  if (!project(cam_to, w_to, h_to, to.position, o_to, pixel, jitter)) return job;  // off screen
  // RS-main Eq. 14-16 (restir/reprojection.h); grazing views fail the shift (docs/ARCHITECTURE.md, Robustness).
  PrimaryView v_from = primary_view(from.position, from.geo_normal, lens_point(cam_from, y.lens), normalize(cam_from.forward.xyz));
  PrimaryView v_to = primary_view(to.position, to.geo_normal, o_to, normalize(cam_to.forward.xyz));
  float area_ratio = from.area > 0.0 ? to.area / from.area * (y1_to.jacobian / x1_from.jacobian) : 0.0;  // |dy_1/dx_1|
  job.camera_ratio = reprojection_jacobian(v_from, v_to, area_ratio, pixel_area(cam_from.right.xyz, cam_from.up.xyz, w_from, h_from),
                                           pixel_area(cam_to.right.xyz, cam_to.up.xyz, w_to, h_to));
  if (!(job.camera_ratio > 0.0)) {
    job.reason = SHIFT_FAIL_JACOBIAN;
    return job;
  }
  job.pixel = vec2(pixel);
  job.y.jitter = jitter;
  job.y.time = time_to;
  job.distance = length(to.position - o_to);
  job.ray_origin = o_to;
  job.ray_dir = job.distance > 0.0 ? (to.position - o_to) / job.distance : vec3(0.0, 0.0, 1.0);
  job.ok = true;
  return job;
}

// After a splat's front-layer attempt failed because its camera ray found a nearer surface: the
// deeper domain it may land in instead (ML 4.2, Fig. 3): the active domain of the target pixel whose
// depth range holds x_1's distance, whose restricted query the next run_shift traces. False when
// x_1 is not hidden, or no range holds it (the sample is then rejected). With layers by rank
// (k_layer_stepping) the camera ray is walked to x_1 instead (ML Fig. 2), and the next query starts
// just beyond the surface in front of it.
bool splat_deeper(INOUT(ShiftJob) job, ShiftResult failed) {
  if (!multilayer() || !job.splat || job.layer != 0u || failed.reason != SHIFT_FAIL_PRIMARY || !hidden_at(failed.primary_t, job.distance))
    return false;
  if (k_layer_stepping) {
    LayerWalk w = walk_to_point(job.prev, job.ray_origin, job.ray_dir, job.y.x1, job.distance);
    counter_add(COUNTER_SPLAT_STEP_RAYS, w.rays);
    if (w.layer == 0u || w.layer >= restir_layers()) return false;
    if ((domain_range_in(job.prev, domain_in(job.prev, uvec2(job.pixel), w.layer)).flags & DOMAIN_ACTIVE) == 0u) return false;
    job.layer = w.layer;
    job.t_min = w.t_start;
    job.t_max = RAY_UNBOUNDED;
    return true;
  }
  float l;
  float r;
  uint layer = deep_layer_by_range(job.prev, uvec2(job.pixel), job.distance, l, r);
  if (layer == 0u) return false;
  job.layer = layer;
  job.t_min = l;
  job.t_max = r;
  return true;
}

// The gather shift of y into `pixel` of the current or previous frame (subpixel position kept).
ShiftJob gather_prepare(bool prev, vec2 pixel, PathSample y) {
  ShiftJob job;
  job.splat = false;
  job.prev = prev;
  job.pixel = pixel;
  job.y = y;
  job.ok = true;
  job.reason = SHIFT_OK;
  job.camera_ratio = 1.0;
  job.time_ratio = 1.0;
  job.layer = 0u;
  job.t_min = 0.0;
  job.t_max = RAY_UNBOUNDED;
  job.distance = 0.0;
  job.ray_origin = vec3(0.0);
  job.ray_dir = vec3(0.0, 0.0, 1.0);
  return job;
}

// The gather shift of y into the deep domain (pixel, layer) of the previous or current frame whose
// depth range is [t_min, t_max] (restir-multilayer's deep backup, restir_splat_resample.comp): the
// domain of ML Eq. 4, so the offset path's primary vertex is the first hit from L_i r within D_i,
// and the camera ray must be blocked before L_i (gather_hidden).
ShiftJob gather_prepare_deep(bool prev, vec2 pixel, PathSample y, uint layer, float t_min, float t_max) {
  ShiftJob job = gather_prepare(prev, pixel, y);
  job.layer = layer;
  job.t_min = t_min;
  job.t_max = t_max;
  return job;
}

// Whether a gather job into a deep domain of the previous frame (the deep backup's) has its camera
// ray blocked before the domain's depth range (ML Eq. 4: the primary vertex is hidden from x_0), as
// restir_initial.comp tests a deep domain's canonical camera rays; true for every other job. One
// any-hit query in the previous frame's TLAS only: lavapipe inlines a traversal per call site and
// per TLAS, and this one needs no other.
bool gather_hidden(ShiftJob job, INOUT(uint) rays) {
  if (!job.ok || job.splat || job.layer == 0u || !job.prev) return true;
  vec3 origin;
  vec3 dir;
  primary_ray(camera_at(true, job.y.time), job.pixel, job.y.jitter, job.y.lens, origin, dir);
  RayHit h;
  rays++;
  return trace_query_in(true, origin, dir, job.t_min, true, h);
}

// After shift_path: a splat's primary ray must have found x_1's triangle again (visibility of y_1
// from y_0, RS-main 4.1.1); the Jacobian of the whole shift. Fails the result where needed.
float shift_finish(ShiftJob job, INOUT(ShiftResult) r) {
  if (r.reason == SHIFT_OK && job.splat &&
      (r.x1.instance != job.y.x1.instance || r.x1.geometry != job.y.x1.geometry || r.x1.triangle != job.y.x1.triangle))
    r = shift_fail(r, SHIFT_FAIL_PRIMARY);
  if (r.reason != SHIFT_OK) return 0.0;
  float j = r.jacobian * job.camera_ratio;  // the path's part (shift_path) and the camera's
  if (!(j >= 1.0 / SHIFT_MAX_JACOBIAN && j <= SHIFT_MAX_JACOBIAN)) {
    r = shift_fail(r, SHIFT_FAIL_JACOBIAN);
    return 0.0;
  }
  r.jacobian = j * job.time_ratio;  // the time factor is exact, outside the range check
  return r.jacobian;
}

// Runs a prepared job (its shift_path call is the caller's one call site when used in a loop).
ShiftResult run_shift(ShiftJob job, bool suffix_changed) {
  if (!job.ok) return shift_none(job.reason);
  // A splat carries its camera sample; its primary ray must find x_1 again (within the layer's range).
  // A gather into a deep domain restricts its primary ray to the domain's depth range (ML Eq. 4).
  DomainPrimary dp = job.splat ? domain_primary_splat(job.y.x1, job.t_min, job.t_max) : domain_primary_free();
  dp.t_min = job.t_min;
  dp.t_max = job.t_max;
  return shift_path(job.prev, job.pixel, dp, job.y, suffix_changed);
}

#endif
