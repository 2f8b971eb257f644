// Suffix replay (docs/ARCHITECTURE.md, "Suffix replay"): the part of a path sample after its
// reconnection vertex x_k, traced again in the frame a temporal shift maps it into, so that a
// sample whose suffix saw a moving object, light or occluder is evaluated exactly there instead of
// being refused as stale (shift_path, restir/path_space.glsl). Only passes that see both frames
// (STRATA_HISTORY) replay; they bind the light tables for the NEE end.
//
// The sample space. Lin et al. 2022 integrate a domain over paths in the solid-angle product
// measure; strata's suffix keeps (restir/reservoir.h) the direction omega_k leaving x_k in x_k's
// surface frame, the random numbers u_j (`seed`) of every later decision, and the structure (the
// segment count n, the technique of the end, and for an NEE end its light candidate). The shift T
// of the suffix, from the base path x into the target frame's path y, is then:
//   omega'_k = R omega_k, R the rotation between x_k's surface frames in the two frames (across a
//   LoD switch, where tau maps x_k onto another tessellation, the instance's own motion instead,
//   with its Jacobian: restir/path_space.glsl, object_fixed_direction);
//   omega'_j = S_{y_j}(u_j), j = k+1 .. n-1, where omega_j = S_{x_j}(u_j) was the base's sample
//   (BSDF sampling at x_j, or for an NEE end the light sample of x_{n-1}; both frames choose the
//   light with this frame's alias table, which HISTORY_LIGHTS_RESELECTED says is the same table);
// a bijection, since it is the identity on (omega_k, u_{k+1}, ..., u_{n-1}) and each S maps u
// one-to-one onto the directions of its support. Its Jacobian in the solid-angle measure is the
// product of the factors (Lin 2022 Eq. 41, applied after x_k):
//   |d omega'_k / d omega_k| = 1  (R is a rotation),
//   |d omega'_j / d omega_j| = p_{x_j}(omega_j) / p_{y_j}(omega'_j)  (du = p d omega on both sides),
// that is suffix_density(x) / suffix_density(y), with suffix_density the product of the densities
// of the sampled directions (restir/reservoir.h). The path's whole Jacobian multiplies it with the
// prefix's density(x) / density(y). The reverse shift (the current sample into the previous frame,
// for the MIS weights) is the same map read backwards, and runs in the previous scene: the previous
// TLAS, instance transforms and light totals (trace_query_in, instance_in, light_pdf_*).
#ifndef STRATA_SUFFIX_REPLAY_GLSL
#define STRATA_SUFFIX_REPLAY_GLSL

#include "restir/path_vertex.glsl"
#include "restir/restir_data.h"
#include "sampling/rng.h"

struct SuffixReplay {
  uint reason;          // SHIFT_OK or SHIFT_FAIL_*
  vec3 xk_radiance;     // the radiance arriving at x_k along -omega'_k, as PathSample.xk_radiance defines it
  float light_pdf_end;  // NEE density of the end from y_{n-1}
  float suffix_density; // of y's sampled directions after x_k
  uint rays;
};

SuffixReplay replay_fail(SuffixReplay r, uint reason) {
  r.reason = reason;
  r.xk_radiance = vec3(0.0);
  return r;
}

// suffix auto: whether y's suffix after x_k is the same in the target frame as in y's own, so that
// its stored radiance and end density are exactly what replay_suffix would compute there. Decided
// without tracing for a suffix of one segment (k + 1 = n: from x_k along omega'_k to the end, an
// emitter or the environment): x_k's instance did not change (so x_k and omega'_k are the same
// world point and direction in both frames), the emitter power total that the end's density
// depends on is equal (light_totals_unchanged, include/scene_lights.glsl),
// and the ray misses the swept box of every instance that changed (ray_meets_change),
// so that it meets the same unchanged surfaces in both frames (x_k on a changed instance lies inside
// that instance's box, so the first test only saves the loop). Longer suffixes are replayed: their
// later vertices are not known without tracing them.
bool suffix_unchanged(bool prev, PathSample y, Vertex xk, vec3 dk) {
  if (y.k + 1u != y.segments || instance_changes(y.xk.instance) != 0u) return false;
  // An end at a punctual light that moved is not where the stored suffix has it.
  if (k_punctual && (y.flags & SAMPLE_PUNCTUAL) != 0u && (history_flags() & HISTORY_LIGHTS_MOVED) != 0u) return false;
  if (!light_totals_unchanged()) return false;
  return !ray_meets_change(prev, xk.position, dk);
}

// The light sample that y's NEE end took at y_{n-1} (candidate y.light_index, its random numbers),
// from vertex v in the current (prev = false) or previous frame: the same light while the light
// table chooses as it did (HISTORY_LIGHTS_RESELECTED), where that frame has it.
bool replay_light_sample(bool prev, PathSample y, Vertex v, out LightSample ls) {
  ls = light_sample_none();
  if ((history_flags() & HISTORY_LIGHTS_RESELECTED) != 0u) return false;
  uint base = dim_vertex(y.segments - 1u) + DIM_NEE + 3u * y.light_index;
  vec3 ul = vec3(rng_dim(y.seed, base), rng_dim(y.seed, base + 1u), rng_dim(y.seed, base + 2u));
  return sample_light_in(prev, v.position, light_receiver(v), ul, ls);
}

// omega'_k of a suffix whose one segment ends at a punctual light (k + 1 = n, SAMPLE_PUNCTUAL): the
// direction from x_k (`xk`, in the target frame) to where that frame has the light. The light is
// x_{k+1}, a fixed point (Jacobian 1, as in shift_path's reconnection to one), so omega'_k is not a
// free dimension of the path and is not kept. False where the light is not the one y chose.
bool punctual_end_direction(bool prev, PathSample y, Vertex xk, out vec3 dk) {
  LightSample ls;
  dk = vec3(0.0, 0.0, 1.0);
  if (!replay_light_sample(prev, y, xk, ls) || !ls.delta) return false;
  dk = ls.direction;
  return true;
}

// Traces y's suffix from x_k (`xk`, loaded in the target frame and entered from the offset path's
// y_{k-1}) along omega'_k = `dk` (world space) in the current (prev = false) or previous frame.
SuffixReplay replay_suffix(bool prev, Vertex xk, vec3 dk, PathSample y) {
  SuffixReplay r;
  r.reason = SHIFT_OK;
  r.xk_radiance = vec3(0.0);
  r.light_pdf_end = 0.0;
  r.suffix_density = 1.0;
  r.rays = 0u;
  uint n = y.segments;
  bool nee = (y.flags & SAMPLE_NEE) != 0u;
  bool escaped = (y.flags & SAMPLE_ESCAPED) != 0u;
  Vertex v = xk;
  vec3 dir = dk;
  vec3 beta = vec3(1.0);  // prod f_s |cos| over y_{k+1} .. y_j
  float pdf = 0.0;        // density of `dir` at y_j (j > k)
  // Segment j leaves y_j. Every segment is one query at a single call site: a closest hit while
  // the path goes on, or the visibility of the light sample of an NEE end.
  bool punctual = k_punctual && (y.flags & SAMPLE_PUNCTUAL) != 0u;  // the NEE end is a punctual light
  for (uint j = y.k; j < n; ++j) {
    bool last = j + 1u == n;
    // An NEE end is the light sample again; from x_k itself only a punctual light's (any other
    // end found from x_k lies along the kept omega'_k).
    bool light_sample = last && nee && (j > y.k || punctual);
    LightSample ls = light_sample_none();
    if (light_sample) {
      if ((history_flags() & HISTORY_LIGHTS_RESELECTED) != 0u) return replay_fail(r, SHIFT_FAIL_STALE);
      if (!replay_light_sample(prev, y, v, ls)) return replay_fail(r, SHIFT_FAIL_REPLAY);
      if (punctual != ls.delta) return replay_fail(r, SHIFT_FAIL_REPLAY);
      // NEE does not sample grazing light (restir_initial.comp): outside the structure.
      if (!isinf(ls.distance) && ls.cos_light < SHIFT_MIN_COS) return replay_fail(r, SHIFT_FAIL_STRUCTURE);
      dir = ls.direction;
    } else if (j > y.k) {
      vec3 fs;
      if (!replay_bsdf_direction(v, y.seed, j, dir, fs, pdf)) return replay_fail(r, SHIFT_FAIL_REPLAY);
      beta *= fs;
      r.suffix_density *= pdf;
    }
    vec3 origin = spawn(v);
    vec3 aim = dir;
    float t_max = RAY_UNBOUNDED;
    if (light_sample && !visibility_ray(origin, v.position, dir, ls.distance, aim, t_max)) return replay_fail(r, SHIFT_FAIL_OCCLUDED);
    RayHit h;
    r.rays++;
    bool hit = trace_query_in(prev, origin, aim, t_max, light_sample, h);
    if (light_sample) {
      if (hit) return replay_fail(r, SHIFT_FAIL_OCCLUDED);
      r.light_pdf_end = ls.pdf;
      if (j == y.k) {
        // A punctual light seen from x_k: shift_path applies x_k's BSDF (its omega'_k points here)
        // and the MIS weight 1 of a delta light; nothing after x_k was sampled.
        r.xk_radiance = ls.radiance;
        return r;
      }
      vec3 fs = scatter(v, dir);
      if (!(luminance(fs) > 0.0)) return replay_fail(r, SHIFT_FAIL_ZERO);
      float m = punctual ? 1.0 : technique_weight(true, ls.pdf, scatter_pdf(v, dir));
      r.xk_radiance = beta * fs * ls.radiance * m;
      r.suffix_density *= ls.pdf;
      return r;
    }
    if (hit == (last && escaped)) return replay_fail(r, SHIFT_FAIL_REPLAY);  // must hit, or escape at an escaped end
    vec3 le;
    float pl;
    if (hit) {
      Vertex w = load_vertex(prev, h, dir, 0.0);  // past the reconnection vertex
      if (!last) {
        v = w;
        continue;
      }
      // An NEE end found along the kept omega'_k (j = k) must lie where NEE samples.
      if (nee && w.cos_in < SHIFT_MIN_COS) return replay_fail(r, SHIFT_FAIL_STRUCTURE);
      le = w.emission;
      pl = light_pdf_emitter(prev, v, w, length(w.position - v.position));
    } else {
      le = environment_radiance(dir);
      pl = light_pdf_environment(prev, dir);
    }
    if (!(luminance(le) > 0.0)) return replay_fail(r, SHIFT_FAIL_ZERO);
    r.light_pdf_end = pl;
    // With j = k the end's MIS weight needs the BSDF at x_k, which shift_path applies (as for a
    // kept suffix); otherwise it is part of the radiance arriving at x_k.
    r.xk_radiance = j == y.k ? le : beta * le * technique_weight(false, pl, pdf);
    return r;
  }
  return replay_fail(r, SHIFT_FAIL_STRUCTURE);  // n <= k: no suffix
}

#endif
