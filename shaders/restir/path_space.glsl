// The shift of a path sample into a domain (pixel, frame): Lin et al. 2022's reconnection and
// hybrid shifts in the form strata's path samples take (restir/reservoir.h).
//
// Sample space. A domain's integral is over the subpixel position (box filter, density 1), the lens
// sample, and the directions of the path in solid angle, for paths of two or more segments (what the
// camera ray sees directly is not resampled: restir_initial.comp); the target function is the luminance of
//   f(x) = prod_{i=1}^{n-1} f_s(x_i) |cos theta_i| * L_e(x_n) * m_t(x)
// where m_t is the MIS weight of the technique t (NEE or BSDF sampling) that produced the last
// vertex: the technique is part of the sample, so both techniques' candidates partition the space.
//
// The shift. The offset path keeps the subpixel position and lens sample (Jacobian 1), replays the
// BSDF directions at y_1 .. y_{k-2} from the sample's random numbers (Jacobian p(x)/p(y), Lin 2022
// Eq. 41 — with the lobe-mixture density this is exact: in primary-sample space the map is the
// identity), and reconnects y_{k-1} to the kept vertex x_k (Jacobian of the solid angle at y_{k-1},
// cos theta_y / |x_k - y_{k-1}|^2 over the base path's, times the ratio of x_k's triangle areas when
// x_k's object scaled). Everything after x_k is kept. With k = 0 the whole path is replayed. The
// product of these factors is stored per path as its `density`, and every Jacobian is
//   |dy/dx| = density(x) / density(y).
// For the shift to be a bijection the offset path must have the same structure: its first
// reconnectable vertex must be k again (else the shift fails, Lin 2022 section 6.2).
//
// Domains with a fixed primary vertex (PRIMARY_DOMAIN, the gather methods; docs/ARCHITECTURE.md,
// "Domains and their primary vertex"). There a domain (pixel, frame) is the set of paths that start
// at the pixel's primary vertex of that frame, y_1, the hit of the camera sample the primary pass
// drew for it (the visibility buffer); its integral is the pixel's given that camera sample, and
// the camera sample's own expectation is taken over frames, as pt's is over its samples. The
// sample space is then the directions after y_1 only, the offset path starts at the target
// domain's y_1 (DomainPrimary: no camera ray is traced) and the factors above are unchanged (the
// camera sample's factor was 1). Splat methods keep the camera sample in the sample (RS-main 4.1:
// a splat carries its primary hit), and their shifts trace the camera ray.
//
// Moving scenes. The kept suffix after x_k is known through its radiance. When the scene moved
// between the frames of the two domains, a sample with a non-empty suffix (0 < k < n) is handled
// as restir_suffix_mode() says: SUFFIX_REPLAY traces it again in the target frame (exact, both
// directions: restir/suffix_replay.glsl, where its Jacobian is derived); SUFFIX_CACHED keeps the
// stored radiance (biased: the suffix's light is that of the other frame); SUFFIX_FAIL fails the
// shift (SHIFT_FAIL_STALE); SUFFIX_AUTO replays, except a suffix of one segment that no change can
// reach, whose stored radiance is then what the replay would find (suffix_unchanged). The direction
// leaving x_k is kept in x_k's surface frame in every mode.
#ifndef STRATA_PATH_SPACE_GLSL
#define STRATA_PATH_SPACE_GLSL

#include "restir/path_vertex.glsl"
#include "restir/restir_data.h"
#include "sampling/rng.h"
#ifdef STRATA_HISTORY
#include "restir/suffix_replay.glsl"
#endif

// What a shift did with the sample's suffix after x_k (counted per pass: COUNTER_SUFFIX_*).
const uint SUFFIX_NONE = 0u;      // no suffix (k = 0 or k = n), or the shift failed before it
const uint SUFFIX_KEPT = 1u;      // the stored radiance was used
const uint SUFFIX_REPLAYED = 2u;  // traced again (its rays are in replay_rays)

// The primary vertex of the target domain of a shift: fixed (PRIMARY_DOMAIN: the domain's
// visibility-buffer entry in its frame, with its camera sample), or free (the offset path traces
// the camera ray of the sample's own camera sample).
// A free primary ray may be restricted to a depth range [t_min, t_max] (a deep pixel-layer domain,
// ML Eq. 4: its primary vertex is the first hit from L_i r; restir/layers.glsl), and may have to
// find a given x_1 (a splat: RS-main 4.1.1's visibility of y_1 from y_0): then a ray that finds
// another surface fails the shift at once (SHIFT_FAIL_PRIMARY, with the distance it found in
// ShiftResult::primary_t), instead of tracing a path the splat then refuses.
struct DomainPrimary {
  bool is_fixed;
  GpuPrimaryHit hit;
  uint entry;        // fixed: the index of `hit` in its frame's visibility buffer
  float t_min;       // free: the primary ray starts at origin + t_min dir ...
  float t_max;       // ... and ends at origin + t_max dir
  bool check_x1;     // free: the primary ray must hit x1's triangle
  SurfacePoint x1;
};

DomainPrimary domain_primary_free() {
  DomainPrimary d;
  d.is_fixed = false;
  d.entry = 0u;
  d.hit.t = 0.0;
  d.hit.instance = 0u;
  d.hit.geometry = 0u;
  d.hit.triangle = 0u;
  d.hit.bary = vec2(0.0);
  d.hit.lod = 0u;
  d.hit.flags = 0u;
  d.hit.jitter = vec2(0.5);
  d.hit.lens = 0u;
  d.hit.time = 0.0;
  d.t_min = 0.0;
  d.t_max = RAY_UNBOUNDED;
  d.check_x1 = false;
  d.x1 = surface_none();
  return d;
}

// The free primary of a splat of a path whose primary hit is x1, within [t_min, t_max] of its camera ray.
DomainPrimary domain_primary_splat(SurfacePoint x1, float t_min, float t_max) {
  DomainPrimary d = domain_primary_free();
  d.t_min = t_min;
  d.t_max = t_max;
  d.check_x1 = true;
  d.x1 = x1;
  return d;
}

// The domain of visibility-buffer entry `h`, at index `entry` of its frame's buffer, when the frame
// fixes primary vertices, else free.
DomainPrimary domain_primary(GpuPrimaryHit h, uint entry) {
  DomainPrimary d = domain_primary_free();
  if (primary_mode() != PRIMARY_DOMAIN) return d;
  d.is_fixed = true;
  d.hit = h;
  d.entry = entry;
  return d;
}

struct ShiftResult {
  uint reason;       // SHIFT_OK or SHIFT_FAIL_*
  vec3 f;            // f of the offset path in the domain (rgb; its luminance is p-hat)
  float density;     // replay density of the offset path
  float jacobian;    // |dy/dx| = density(x) / density(y), bounded (shift_jacobian); 0 when the shift failed.
                     // A splat multiplies in its camera and time factors (restir/splat.glsl).
  SurfacePoint x1;   // its primary hit
  SurfacePoint xk;   // its reconnection vertex: the base path's, or tau of it across a LoD switch
  CameraSample camera;  // its camera sample: the sample's own, or the target domain's when fixed
  uint rays;         // all rays traced, replay_rays included
  // The offset path's suffix as its sample stores it (restir/reservoir.h): the base's, unless replayed.
  vec3 xk_radiance;
  float light_pdf_end;
  float suffix_density;
  vec3 xk_direction;  // omega_k in x_k's surface frame (the base's; re-expressed at a mapped x_k)
  uint suffix;       // SUFFIX_NONE | SUFFIX_KEPT | SUFFIX_REPLAYED
  uint replay_rays;
  float primary_t;   // a free primary ray's hit distance from the camera (0: none; a check_x1 failure says where)
};

ShiftResult shift_none(uint reason) {
  ShiftResult r;
  r.reason = reason;
  r.f = vec3(0.0);
  r.density = 0.0;
  r.jacobian = 0.0;
  r.x1 = surface_none();
  r.xk = surface_none();
  r.camera.jitter = vec2(0.5);
  r.camera.lens = vec2(0.5);
  r.camera.time = 0.0;
  r.rays = 0u;
  r.xk_radiance = vec3(0.0);
  r.light_pdf_end = 0.0;
  r.suffix_density = 1.0;
  r.xk_direction = vec3(0.0, 0.0, 1.0);
  r.suffix = SUFFIX_NONE;
  r.replay_rays = 0u;
  r.primary_t = 0.0;
  return r;
}

ShiftResult shift_fail(ShiftResult r, uint reason) {
  r.reason = reason;
  r.f = vec3(0.0);
  r.density = 0.0;
  r.jacobian = 0.0;
  return r;
}

// The offset path's camera sample in the target domain: the domain's own where its primary vertex is
// fixed, else the sample's (kept by the shift: Jacobian 1).
CameraSample shift_camera(DomainPrimary dp, PathSample y) {
  if (dp.is_fixed) return primary_camera_sample(dp.hit);
  CameraSample c;
  c.jitter = y.jitter;
  c.lens = y.lens;
  c.time = y.time;
  return c;
}

// Jacobian |dy/dx| of a shift from a path of replay density `base` to one of density `offset`,
// bounded like every other Jacobian (thresholds.h); 0 fails the shift.
float shift_jacobian(float base, float offset) {
  if (!(base > 0.0) || !(offset > 0.0)) return 0.0;
  float j = base / offset;
  if (!(j >= 1.0 / SHIFT_MAX_JACOBIAN && j <= SHIFT_MAX_JACOBIAN)) return 0.0;
  return j;
}

// The sample T(y) that a successful shift of y produced, as a reservoir keeps it.
PathSample shifted_sample(PathSample y, ShiftResult s) {
  y.x1 = s.x1;
  y.xk = s.xk;
  y.jitter = s.camera.jitter;
  y.lens = s.camera.lens;
  y.time = s.camera.time;
  y.density = s.density;
  y.xk_radiance = s.xk_radiance;
  y.light_pdf_end = s.light_pdf_end;
  y.suffix_density = s.suffix_density;
  y.xk_direction = s.xk_direction;
  return y;
}

// Whether y_{k-1} = v sees x_k (at `dist` along d). `to_light`: x_k is no surface: the environment
// along d, or a punctual light `dist` away (infinite for a directional light), which any hit blocks.
// A visibility ray aimed at a point on a surface can hit that same surface just short of it: the
// traversal's intersection and the resolved point differ by rounding (on lavapipe by 1e-4 of the
// distance and more on rotated instances, where 0.5-1% of the temporal shifts of a static
// Cornell box failed so, each a path that could never be reused and whose history went dark). So a
// blocked ray is traced once more for its closest hit, and counts as visible when that hit is x_k's
// own mesh part within RECONNECT_SELF_TOLERANCE of the distance (restir/thresholds.h). Both
// queries go through the single call site of trace_query_in. A blocking hit that the first query
// reports short of that band settles it without the second: the closest hit lies no farther.
bool reconnection_visible(bool prev, Vertex v, vec3 d, float dist, bool to_light, SurfacePoint xk, INOUT(uint) rays) {
  bool to_environment = to_light;
  vec3 origin = spawn(v);
  bool punctual_point = k_punctual && to_light && dist > 0.0 && !isinf(dist);  // a point or spot light
  // Aimed at a point from the spawn origin, and its distance measured from there (aim_ray).
  if ((!to_light || punctual_point) && !aim_ray(origin, v.position + d * dist, d, dist)) return false;
  for (uint attempt = 0u; attempt < 2u; ++attempt) {
    bool any_hit = attempt == 0u;
    float t_max = to_environment ? RAY_UNBOUNDED : (any_hit ? dist * (1.0 - SHADOW_RAY_SHORTEN) : dist * (1.0 + RECONNECT_SELF_TOLERANCE));
    if (punctual_point) t_max = dist * (1.0 - SHADOW_RAY_SHORTEN);
    RayHit h;
    rays++;
    bool hit = trace_query_in(prev, origin, d, t_max, any_hit, h);
    if (any_hit) {
      if (!hit) return true;
      if (to_environment || h.t < dist * (1.0 - RECONNECT_SELF_TOLERANCE)) return false;
    } else {
      return hit && h.instance == xk.instance && h.geometry == xk.geometry && h.t >= dist * (1.0 - RECONNECT_SELF_TOLERANCE);
    }
  }
  return false;
}

#ifdef STRATA_HISTORY
// omega_k of a reconnection vertex that tau mapped onto another LoD level (LOD 4.4), in the target
// frame: the stored direction (`local`, in x_k's surface frame at its own level, in the other frame)
// taken to world space there and carried by the instance's own motion,
//   omega'_k = A omega_k / |A omega_k|,  A = L_target L_source^-1 (the transforms' linear parts),
// whose solid-angle Jacobian is |det A| / |A omega_k|^3 (1 for a rigid or static instance). Within one
// level omega_k turns with x_k's surface frame (surface_to_world); across a switch that frame turns
// with the other tessellation's shading normal, which for a small light (lod-cliff's sun, 0.6 deg)
// points the replayed suffix past it. The map is a bijection (its inverse is the same construction
// from the target side, A^-1), so the shift stays one. False when A is singular.
bool object_fixed_direction(bool prev, SurfacePoint stored, vec3 local, out vec3 dir, out float jacobian) {
  dir = vec3(0.0, 0.0, 1.0);
  jacobian = 0.0;
  ResolvedSurface own = resolve_surface_as(!prev, stored, LOD_VERTEX_NONE);  // x_k in its own frame and level
  if (own.reason != RESOLVE_OK) return false;
  vec3 w = frame_to_world(own.hit.shading_normal, local);
  // L_source^-1 is the transpose of the source frame's normal matrix (the inverse transpose of L).
  mat3 a = mat3(instance_in(prev, stored.instance).object_to_render) * transpose(mat3(instance_in(!prev, stored.instance).normal_to_render));
  vec3 aw = a * w;
  float la = length(aw);
  jacobian = abs(determinant(a)) / (la * la * la);
  if (!(la > 0.0) || !(jacobian > 0.0) || isinf(jacobian)) return false;
  dir = aw / la;
  return true;
}
#endif

// Evaluates the sample y, shifted into the domain of `pixel` in the current (prev = false) or the
// previous frame, whose primary vertex is `dp`. suffix_changed: the scene moved between y's frame
// and the domain's frame.
ShiftResult shift_path(bool prev, vec2 pixel, DomainPrimary dp, PathSample y, bool suffix_changed) {
  ShiftResult r = shift_none(SHIFT_OK);
  r.xk = y.xk;
  r.xk_radiance = y.xk_radiance;
  r.light_pdf_end = y.light_pdf_end;
  r.suffix_density = y.suffix_density;
  r.xk_direction = y.xk_direction;
  uint n = y.segments;
  uint k = y.k;
  bool escaped = (y.flags & SAMPLE_ESCAPED) != 0u;
  bool nee = (y.flags & SAMPLE_NEE) != 0u;
  bool punctual = k_punctual && (y.flags & SAMPLE_PUNCTUAL) != 0u;  // an NEE end at a punctual light
  // Paths of one segment are not resampled (restir_initial.comp): no reservoir holds one.
  if (n < 2u || n > restir_max_segments() || k > n || k == 1u) return shift_fail(r, SHIFT_FAIL_STRUCTURE);
  bool has_suffix = k != 0u && k < n;
  if (suffix_changed && has_suffix && restir_suffix_mode() == SUFFIX_FAIL) return shift_fail(r, SHIFT_FAIL_STALE);
#ifdef STRATA_HISTORY
  bool replay = suffix_changed && has_suffix && (restir_suffix_mode() == SUFFIX_REPLAY || restir_suffix_mode() == SUFFIX_AUTO);
#else
  bool replay = false;  // one frame: nothing to replay
#endif
  // The pure reconnection shift replays only the camera sample and reconnects at x_2.
  if (restir_shift_mode() == SHIFT_RECONNECTION && k != 2u) return shift_fail(r, SHIFT_FAIL_STRUCTURE);

  // One loop finds every segment by replay: segment 0 is the camera ray (the sample's camera
  // sample kept; with a fixed primary vertex the domain's, whose hit is known), segment j >= 1
  // leaves y_j in the direction replayed from the sample's random numbers. With k >= 2 the loop
  // ends at y_{k-1}; with k = 0 its last segment finds the path's end.
  // (A single tracing call site: lavapipe inlines a BVH traversal per call site.)
  uint last_traced = k >= 2u ? k - 2u : n - 1u;
  r.camera = shift_camera(dp, y);
  vec3 origin;
  vec3 dir;
  primary_ray(camera_at(prev, r.camera.time), pixel, r.camera.jitter, r.camera.lens, origin, dir);
  vec3 f_prefix = vec3(1.0);
  float density = 1.0;
  float pdf = 0.0;
  float camera_distance = 0.0;
  vec3 le = vec3(0.0);      // k = 0: emission at the end
  float pl = 0.0;           // k = 0: its light-sampling density
  float map_jacobian = 1.0;  // LOD Eq. 6 of a mapped x_k
  Vertex v;
  for (uint j = 0u; j <= last_traced; ++j) {
    if (j > 0u) {
      vec3 fs;
      if (!replay_bsdf_direction(v, y.seed, j, dir, fs, pdf)) return shift_fail(r, SHIFT_FAIL_REPLAY);
      origin = spawn(v);
      f_prefix *= fs;
      density *= pdf;
    }
    bool path_end = k == 0u && j == n - 1u;  // this segment must find the path's last vertex
    RayHit h;
    bool found;
    bool fixed_vertex = j == 0u && dp.is_fixed;
    if (fixed_vertex) {
      found = primary_hit(dp.hit, h);  // the domain's primary vertex y_1, loaded by the primary stage
    } else {
      r.rays++;
      float t0 = j == 0u ? dp.t_min : 0.0;  // a deep domain's primary ray starts at L_i (ML Eq. 4)
      found = trace_closest_in(prev, origin + dir * t0, dir, j == 0u ? dp.t_max - t0 : RAY_UNBOUNDED, h);
      if (j == 0u) {
        h.t += t0;
        r.primary_t = found ? h.t : 0.0;
        if (dp.check_x1 && (!found || h.instance != dp.x1.instance || h.geometry != dp.x1.geometry || h.triangle != dp.x1.triangle))
          return shift_fail(r, SHIFT_FAIL_PRIMARY);
      }
    }
    if (!found) {
      if (!(path_end && escaped)) return shift_fail(r, j == 0u ? SHIFT_FAIL_PRIMARY : SHIFT_FAIL_REPLAY);
      if (rule_end(v, true, 0.0, camera_distance, 1.0)) return shift_fail(r, SHIFT_FAIL_STRUCTURE);
      le = environment_radiance(dir);
      pl = light_pdf_environment(prev, dir);
      break;
    }
    if (path_end && escaped) return shift_fail(r, j == 0u ? SHIFT_FAIL_PRIMARY : SHIFT_FAIL_REPLAY);
    float spread = j == 0u ? camera_spread(prev) : 0.0;  // the footprint rule: the target path's primary vertex
    Vertex w = fixed_vertex ? fixed_primary_vertex(prev, dp.hit, dp.entry, h, dir) : load_vertex(prev, h, dir, spread);
    if (j == 0u) {
      r.x1 = w.point;
      camera_distance = length(w.position);
    } else {
      float edge = length(w.position - v.position);
      if (path_end) {
        if (rule_end(v, false, edge, camera_distance, w.cos_in)) return shift_fail(r, SHIFT_FAIL_STRUCTURE);
        le = w.emission;
        pl = light_pdf_emitter(prev, v, w, edge);
      } else if (rule_intermediate(v, w, edge, camera_distance)) {
        return shift_fail(r, SHIFT_FAIL_STRUCTURE);
      }
    }
    v = w;
  }

  if (k >= 2u) {
    // Reconnection of y_{k-1} = v to x_k.
    vec3 d;
    float dist = 0.0;
    float geometry = 1.0;  // cos theta_k / dist^2 (1 for a direction to the environment)
    float area = 1.0;
    float xk_jacobian = 1.0;  // |d tau / dx_k| in barycentric measure (1: x_k's triangle kept)
    Vertex xk;
    bool to_environment = escaped && k == n;
    bool to_punctual = punctual && k == n;
    LightSample lk = light_sample_none();  // x_k as a punctual light
    if (to_environment) {
      d = y.xk_direction;
    } else if (to_punctual) {
      // x_k is the light, where the target frame's record has it. A fixed point: the reconnection
      // Jacobian (Lin 2022 Eq. 41, |dy_k/dx_k| = (cos theta_y / cos theta_x) (|x_k - x_{k-1}|^2 /
      // |y_k - y_{k-1}|^2)) is that of a vertex that does not move in its own measure, the
      // counting measure over the lights, so no cos / dist^2 or area factor enters the density
      // (geometry = area = 1) and the Jacobian is the ratio of the replayed prefix densities alone;
      // 1/d^2 and the spot falloff are in the target function, through lk.radiance.
      if (!punctual_light_at(prev, y.xk.triangle, v.position, light_receiver(v), lk)) return shift_fail(r, SHIFT_FAIL_ZERO);
      d = lk.direction;
      dist = lk.distance;
    } else {
      // x_k moves with its object; across a LoD switch tau maps it (LOD 4.4, "LoD-aware hybrid shift").
      ResolvedSurface rk = resolve_surface_as(prev, y.xk, LOD_VERTEX_RECONNECTION);
#ifdef STRATA_HISTORY
      count_lod_mapping(rk);
#endif
      if (rk.reason != RESOLVE_OK) return shift_fail(r, SHIFT_FAIL_STALE);
      r.xk = rk.point;
      xk_jacobian = rk.jacobian;
      SurfaceHit sk = rk.hit;
      vec3 e = sk.position - v.position;
      float dist2 = dot(e, e);
      if (!(dist2 > 0.0)) return shift_fail(r, SHIFT_FAIL_JACOBIAN);
      dist = sqrt(dist2);
      d = e / dist;
      xk = make_vertex(sk, rk.ray, rk.lod, d, 0.0);  // k >= 2: past the primary vertex
      // A grazing x_k is excluded by the structure rules (NEE drops grazing light samples).
      if (xk.cos_in < SHIFT_MIN_COS) return shift_fail(r, SHIFT_FAIL_STRUCTURE);
      geometry = xk.cos_in / dist2;
      area = xk.area;
      if (k < n) {
        if (!rule_intermediate(v, xk, dist, camera_distance)) return shift_fail(r, SHIFT_FAIL_STRUCTURE);
      } else if (!nee) {
        if (!rule_end(v, false, dist, camera_distance, xk.cos_in)) return shift_fail(r, SHIFT_FAIL_STRUCTURE);
      }
    }
    vec3 fs = scatter(v, d);
    if (!(luminance(fs) > 0.0)) return shift_fail(r, SHIFT_FAIL_ZERO);
    vec3 tail = vec3(0.0);
    vec3 dk = vec3(0.0);  // k < n: the direction leaving x_k, kept in its surface frame
    vec3 fk = vec3(0.0);
    bool punctual_end = punctual && k + 1u == n;  // x_{k+1} is a punctual light: omega_k points at it
    if (k < n) {
      dk = surface_to_world(xk, y.xk_direction);
#ifdef STRATA_HISTORY
      if (punctual_end && replay) {
        // The light where the target frame has it, seen from x_k there (restir/suffix_replay.glsl).
        if (!punctual_end_direction(prev, y, xk, dk)) return shift_fail(r, SHIFT_FAIL_REPLAY);
        r.xk_direction = surface_to_local(xk, dk);
      }
#endif
#ifdef STRATA_HISTORY
      if (xk.point.lod != y.xk.lod) {
        // A mapped x_k: omega_k fixed to the object (object_fixed_direction).
        float dir_jacobian;
        if (!object_fixed_direction(prev, y.xk, y.xk_direction, dk, dir_jacobian)) return shift_fail(r, SHIFT_FAIL_JACOBIAN);
        xk_jacobian *= dir_jacobian;
        r.xk_direction = surface_to_local(xk, dk);
      }
#endif
      fk = scatter(xk, dk);
      if (!(luminance(fk) > 0.0)) return shift_fail(r, SHIFT_FAIL_ZERO);
#ifdef STRATA_HISTORY
      if (replay && restir_suffix_mode() == SUFFIX_AUTO && suffix_unchanged(prev, y, xk, dk)) replay = false;
#endif
      if (!replay) {
        float m = 1.0;
        if (k + 1u == n && !punctual_end) m = technique_weight(nee, y.light_pdf_end, scatter_pdf(xk, dk));
        tail = fk * y.xk_radiance * m;
        r.suffix = SUFFIX_KEPT;
      }
    } else if (to_environment) {
      if (!nee && !rule_end(v, true, 0.0, camera_distance, 1.0)) return shift_fail(r, SHIFT_FAIL_STRUCTURE);
      tail = environment_radiance(d) * technique_weight(nee, light_pdf_environment(prev, d), scatter_pdf(v, d));
    } else if (to_punctual) {
      tail = lk.radiance;  // NEE is the light's only strategy: MIS weight 1
      r.light_pdf_end = lk.pdf;
    } else {
      float pl_k = light_pdf_emitter(prev, v, xk, dist);
      tail = xk.emission * technique_weight(nee, pl_k, scatter_pdf(v, d));
    }
    if (!replay && !(luminance(tail) > 0.0)) return shift_fail(r, SHIFT_FAIL_ZERO);
    if (!reconnection_visible(prev, v, d, dist, to_environment || to_punctual, r.xk, r.rays)) return shift_fail(r, SHIFT_FAIL_OCCLUDED);
#ifdef STRATA_HISTORY
    if (replay) {
      // The suffix in this frame (restir/suffix_replay.glsl), after the cheaper tests passed.
      SuffixReplay sr = replay_suffix(prev, xk, dk, y);
      r.rays += sr.rays;
      r.replay_rays = sr.rays;
      r.suffix = SUFFIX_REPLAYED;
      if (sr.reason != SHIFT_OK) return shift_fail(r, sr.reason);
      float m = 1.0;
      if (k + 1u == n && !punctual_end) m = technique_weight(nee, sr.light_pdf_end, scatter_pdf(xk, dk));
      tail = fk * sr.xk_radiance * m;
      r.xk_radiance = sr.xk_radiance;
      r.light_pdf_end = sr.light_pdf_end;
      r.suffix_density = sr.suffix_density;
      if (!(luminance(tail) > 0.0)) return shift_fail(r, SHIFT_FAIL_ZERO);
    }
#endif
    r.f = f_prefix * fs * tail;
    r.density = density / (geometry * area);
    map_jacobian = xk_jacobian;
  } else {
    // k = 0: the loop replayed the whole path.
    r.f = f_prefix * le * technique_weight(false, pl, pdf);
    r.density = density;
  }
  if (!(luminance(r.f) > 0.0)) return shift_fail(r, SHIFT_FAIL_ZERO);
  if (any(isnan(r.f)) || any(isinf(r.f)) || !(r.density > 0.0) || isinf(r.density)) return shift_fail(r, SHIFT_FAIL_JACOBIAN);
  // |dy/dx| (Lin 2022 Eq. 41 over the prefix and reconnection; a replayed suffix multiplies in
  // suffix_density(x) / suffix_density(y), restir/suffix_replay.glsl; a kept one is unchanged).
  // A mapped x_k multiplies in |d tau / dx_k| (LOD 4.4, "Jacobians"; its area part is in `area`).
  if (r.suffix == SUFFIX_REPLAYED) r.jacobian = shift_jacobian(y.density * y.suffix_density * map_jacobian, r.density * r.suffix_density);
  else r.jacobian = shift_jacobian(y.density * map_jacobian, r.density);
  return r;
}

#ifdef STRATA_HISTORY
// Counts a temporal shift's suffix (COUNTER_SUFFIX_*); the rays of a replay also go to
// `replay_rays_counter` (the pass's slot). Needs the pass's counters (restir/restir_pass.glsl).
void count_suffix(ShiftResult s, uint replay_rays_counter) {
  if (s.suffix == SUFFIX_KEPT) counter_add(COUNTER_SUFFIX_KEPT, 1u);
  if (s.suffix != SUFFIX_REPLAYED) return;
  counter_add(COUNTER_SUFFIX_REPLAYED, 1u);
  counter_add(replay_rays_counter, s.replay_rays);
}
#endif

#endif
