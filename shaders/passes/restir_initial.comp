#version 460
// Pass `initial` (docs/ARCHITECTURE.md, Methods; RS-main 3.4): the canonical sample of each pixel by
// resampled importance sampling over the sub-paths of N_init paths. With PRIMARY_DOMAIN (the gather
// methods) all of them start at the pixel's primary vertex of this frame, the visibility buffer's
// hit (docs/ARCHITECTURE.md, "Domains and their primary vertex"); otherwise each traces its own
// camera ray with its own camera sample. Each path is the path
// tracer's (NEE with `light_candidates` samples per vertex, BSDF sampling, power-heuristic MIS);
// every NEE connection and every emitter or environment hit is one candidate, with resampling
// weight w = m_i p-hat(X) / p(X) = luminance of its MIS-weighted contribution over
// N_init * (candidates of its technique) (RS-main Eq. 4 with W_X = 1/p). Russian roulette starts only
// after the reconnection vertex x_k is fixed, so the replayed prefix never depends on it.
//
// The reservoirs hold paths of two or more segments only. What the camera ray itself finds (x_1's
// emission, or the environment when it escapes: the paths of one segment) is estimated by plain
// Monte Carlo over the same N_init camera rays and added by the shade pass (restir_pass.glsl,
// primary_emission_index). Resampling it would be unbiased but ruins spatial reuse: in a pixel that
// sees an emitter, L_e(x_1) is almost all of the integral of p-hat, so the W of any longer path such a
// reservoir holds is about L_e(x_1) / p-hat(y); no shift can carry the emission part to a pixel that
// does not see the emitter, while that path shifts fine, and lands on a dim neighbour with the
// emitter pixel's whole value (a resampling weight up to p-hat_j W_j = L_e).
//
// restir-multilayer: a second dispatch (SPEC_DOMAIN_LIST) draws the canonical samples of the active
// deep domains of the compacted list (ML Sec. 5: "we generate canonical samples for each active
// domain"). Each estimates I_i of ML Eq. 3 over the domain A_i of Eq. 4: the camera ray's primary
// vertex is its first hit from x_0 + L_i r within the depth range D_i, and only where something
// hides it from x_0 (the path's contribution g drops V(x_0, x_1)).
#extension GL_EXT_ray_query : require
#extension GL_GOOGLE_include_directive : require

layout(local_size_x = 8, local_size_y = 8, local_size_z = 1) in;

#include "include/scene_bridge.glsl"
#include "sampling/russian_roulette.h"
#include "restir/restir_pass.glsl"
#include "restir/path_space.glsl"
#include "restir/restir_limits.h"
#include "restir/centre_surface.glsl"
#include "restir/layers.glsl"


layout(set = 0, binding = BINDING_PRIMARY, std430) readonly buffer Primary { GpuPrimaryHit b_primary[]; };
layout(set = 0, binding = BINDING_DOMAIN_LIST, std430) readonly buffer DomainList { uint b_domain_list[]; };
layout(set = 0, binding = BINDING_DOMAIN_ARGS, std430) readonly buffer DomainArgs { GpuDomainArgs b_domain_args; };
layout(set = 0, binding = BINDING_SPLAT_OFFSETS, std430) readonly buffer SplatOffsets { uint b_splat_offsets[]; };
layout(constant_id = SPEC_DOMAIN_LIST) const bool k_domain_list = false;

// The candidates of a front-layer pixel: disocclusion_initial_candidates where this frame's splat
// counting sort (run before this pass) landed no splat, the ML paper's "more initial spp" baseline
// (Fig. 9); else initial_candidates. restir-multilayer boosts only the disoccluded ones
// (DOMAIN_DISOCCLUDED, domain_build.comp): a disoccluded pixel no splat reached shows a surface no
// deep domain carried, with no history to reuse; a landing hole on a surface that stayed in view
// is not boosted. Unbiased either way: geometry and the splats' landing fix the count before any
// candidate.
uint initial_candidates_of(uint domain) {
  uint boost = u_restir.disocclusion_initial_candidates;
  if (boost == 0u || (u_frame.history_flags & HISTORY_VALID) == 0u) return u_restir.initial_candidates;
  if (b_splat_offsets[domain + 1u] != b_splat_offsets[domain]) return u_restir.initial_candidates;
  if (multilayer() && (b_domains[domain].flags & DOMAIN_DISOCCLUDED) == 0u) return u_restir.initial_candidates;
  counter_add(COUNTER_DISOCCLUSION_BOOSTED, 1u);
  return boost;
}

uint g_rays = 0u;
GrisState g_state;
Reservoir g_selected;
vec3 g_selected_f;
vec3 g_primary_emission;  // sum over the camera rays of what they see, over N_init
Rng g_select_rng;
GpuDomainRange g_range;  // a deep domain's depth range (SPEC_DOMAIN_LIST)
uint g_layer;            // and its layer

// Streams one candidate: sample y with f(y) and its resampling weight.
void offer(PathSample y, vec3 f, float w) {
  float p_hat = luminance(f);
  if (gris_stream_path(g_state, w, p_hat, f, 0.0, 0u, rng_next_float(g_select_rng))) {
    g_selected.y = y;
    g_selected_f = f;
  }
}

PathSample sample_begin(uint key, vec2 jitter, vec2 lens, float time) {
  PathSample y = reservoir_empty().y;
  y.seed = key;
  y.jitter = jitter;
  y.lens = lens;
  y.time = time;
  y.flags = SAMPLE_VALID;
  return y;
}

// One path of the initial estimator: streams all of its candidates.
void trace_candidates(uvec2 pixel, uint key, float n_init) {
  bool domain_primary = u_frame.primary_mode == PRIMARY_DOMAIN;
  GpuPrimaryHit ph;
  CameraSample cs;
  if (domain_primary) {
    ph = b_primary[pixel_index(pixel)];
    cs = primary_camera_sample(ph);
  } else {
    cs = camera_sample(key);
  }
  vec3 origin;
  vec3 dir;
  primary_ray(camera_at(false, cs.time), vec2(pixel), cs.jitter, cs.lens, origin, dir);
  PathSample y = sample_begin(key, cs.jitter, cs.lens, cs.time);
  RayHit h;
  bool found;
  if (domain_primary) {
    found = primary_hit(ph, h);  // the domain's primary vertex: no ray
  } else if (k_domain_list && k_layer_stepping) {
    found = walk_to_layer(origin, dir, g_layer, h, g_rays);  // a deep domain by rank (ML Eq. 3)
    if (!found) return;
  } else if (k_domain_list) {
    // A deep domain (ML Eq. 4): the first hit from x_0 + L_i r within D_i, hidden from x_0.
    g_rays += 2u;
    found = trace_closest(origin + dir * g_range.range_min, dir, g_range.range_max - g_range.range_min, h) &&
            !trace_visible(origin, dir, g_range.range_min);
    if (!found) return;  // no path of this camera ray is in the domain; what it sees is the front layer's
  } else {
    g_rays++;
    found = trace_closest(origin, dir, RAY_UNBOUNDED, h);
  }
  if (!found) {
    g_primary_emission += environment_radiance(dir) / n_init;  // one segment: not resampled
    return;
  }
  Vertex v = domain_primary ? fixed_primary_vertex(false, ph, pixel_index(pixel), h, dir)
                            : load_vertex(false, h, dir, camera_spread(false));  // the footprint rule at the primary vertex
  y.x1 = v.point;
  g_primary_emission += v.emission / n_init;  // one segment: not resampled
  float camera_distance = length(v.position);
  float light_count = float(u_restir.light_candidates);

  vec3 f_prefix = vec3(1.0);   // prod f_s |cos| over x_1 .. x_{i-1} (unweighted)
  float pdf_path = 1.0;        // density of those directions, with Russian roulette
  float pdf_replay = 1.0;      // densities of the directions the hybrid shift replays
  uint kf = 0u;                // the reconnection vertex, once found
  SurfacePoint xk = surface_none();
  float density_k = 0.0;
  vec3 suffix = vec3(1.0);     // prod f_s |cos| over x_{k+1} .. x_{i-1}
  float pdf_suffix = 1.0;      // densities of the directions sampled at x_{k+1} .. x_{i-1}
  vec3 dir_k = vec3(0.0, 0.0, 1.0);  // leaving x_k, in its surface frame

  for (uint i = 1u; i < u_restir.max_segments; ++i) {
    uint n = i + 1u;
    // Next-event estimation: light_candidates connections from x_i.
    for (uint j = 0u; j < u_restir.light_candidates; ++j) {
      uint base = dim_vertex(i) + DIM_NEE + 3u * j;
      LightSample ls;
      vec3 ul = vec3(rng_dim(key, base), rng_dim(key, base + 1u), rng_dim(key, base + 2u));
      if (!sample_light(v.position, light_receiver(v), ul, ls)) continue;
      bool delta = k_punctual && ls.delta;  // a punctual light (cos_light 1)
      // Grazing light samples are outside every path structure (path_vertex.glsl): energy at
      // |cos| < SHIFT_MIN_COS, a 1e-6 fraction of a Lambertian emitter's output, is not sampled by NEE.
      if (!isinf(ls.distance) && ls.cos_light < SHIFT_MIN_COS) continue;
      vec3 fs = scatter(v, ls.direction);
      if (!(luminance(fs) > 0.0)) continue;
      vec3 origin = spawn(v);
      vec3 aim;
      float t_max;
      if (!visibility_ray(origin, v.position, ls.direction, ls.distance, aim, t_max)) continue;
      g_rays++;
      if (!trace_visible(origin, aim, t_max)) continue;
      float m = delta ? 1.0 : technique_weight(true, ls.pdf, scatter_pdf(v, ls.direction));
      vec3 f = f_prefix * fs * ls.radiance * m;
      PathSample c = y;
      c.segments = n;
      c.flags |= SAMPLE_NEE | (delta ? SAMPLE_PUNCTUAL : (isinf(ls.distance) ? SAMPLE_ESCAPED : 0u));
      c.light_index = j;
      if (kf != 0u) {
        c.k = kf;
        c.xk = xk;
        c.density = density_k;
        c.xk_direction = kf == i ? surface_to_local(v, ls.direction) : dir_k;
        c.suffix_density = kf == i ? 1.0 : pdf_suffix * ls.pdf;
        c.xk_radiance = kf == i ? ls.radiance : suffix * fs * ls.radiance * m;
        c.light_pdf_end = ls.pdf;
      } else {
        // NEE's point is always the reconnection vertex when none came before (a replay of the
        // light sample would find the same point: light sampling does not depend on x_i).
        c.k = n;
        c.flags |= SAMPLE_XK_IS_LAST;
        c.xk_direction = ls.direction;
        c.xk_radiance = ls.radiance;
        c.light_pdf_end = ls.pdf;
        if (delta) {
          // x_k is the light: a fixed point, no area measure at it (path_space.glsl, shift_path).
          c.xk.triangle = ls.light;
          c.density = pdf_replay;
        } else if (isinf(ls.distance)) {
          c.density = pdf_replay;
        } else {
          c.xk.instance = ls.instance;
          c.xk.geometry = ls.geometry;
          c.xk.triangle = ls.triangle;
          c.xk.bary = ls.bary;
          c.xk.lod = instance_in(false, ls.instance).lod;
          c.density = pdf_replay / (ls.cos_light / (ls.distance * ls.distance) * ls.area);
        }
      }
      offer(c, f, luminance(f) / (n_init * light_count * pdf_path * ls.pdf));
    }

    // BSDF sampling: continues the path, and is a candidate when it finds emission.
    uint base = dim_vertex(i) + DIM_BSDF;
    vec3 u = vec3(rng_dim(key, base), rng_dim(key, base + 1u), rng_dim(key, base + 2u));
    vec3 wi;
    vec3 weight;
    float pdf;
    if (!bsdf_sample(v.bsdf, v.wo, u, wi, weight, pdf)) break;
    vec3 d = to_world(wi, v.t, v.b, v.ns);
    if (dot(d, v.ng) <= 0.0) break;
    vec3 fs = weight * pdf;
    g_rays++;
    bool hit = trace_closest(spawn(v), d, RAY_UNBOUNDED, h);
    Vertex w;
    float edge = 0.0;
    vec3 le;
    float pl;
    if (hit) {
      w = load_vertex(false, h, d, 0.0);
      edge = length(w.position - v.position);
      le = w.emission;
      pl = light_pdf_emitter(false, v, w, edge);
    } else {
      le = environment_radiance(d);
      pl = light_pdf_environment(false, d);
    }
    if (luminance(le) > 0.0) {
      float m = technique_weight(false, pl, pdf);
      vec3 f = f_prefix * fs * le * m;
      PathSample c = y;
      c.segments = n;
      c.flags |= hit ? SAMPLE_EMITTER_HIT : SAMPLE_ESCAPED;
      if (kf != 0u) {
        c.k = kf;
        c.xk = xk;
        c.density = density_k;
        c.xk_direction = kf == i ? surface_to_local(v, d) : dir_k;
        c.suffix_density = kf == i ? 1.0 : pdf_suffix * pdf;
        c.xk_radiance = kf == i ? le : suffix * fs * le * m;
        c.light_pdf_end = pl;
      } else if (rule_end(v, !hit, edge, camera_distance, hit ? w.cos_in : 1.0)) {
        c.k = n;
        c.flags |= SAMPLE_XK_IS_LAST;
        c.xk_direction = d;
        c.xk_radiance = le;
        c.light_pdf_end = pl;
        if (hit) {
          c.xk = w.point;
          c.density = pdf_replay / (w.cos_in / (edge * edge) * w.area);
        } else {
          c.density = pdf_replay;
        }
      } else {
        c.k = 0u;
        c.density = pdf_replay * pdf;
        c.light_pdf_end = pl;
      }
      offer(c, f, luminance(f) / (n_init * pdf_path * pdf));
    }
    if (!hit) break;

    // Advance to x_{i+1}.
    if (kf == i) dir_k = surface_to_local(v, d);
    if (kf != 0u && i > kf) {
      suffix *= fs;
      pdf_suffix *= pdf;
    }
    f_prefix *= fs;
    pdf_path *= pdf;
    if (kf == 0u && rule_intermediate(v, w, edge, camera_distance)) {
      kf = i + 1u;
      xk = w.point;
      density_k = pdf_replay / (w.cos_in / (edge * edge) * w.area);
      suffix = vec3(1.0);
    }
    if (kf == 0u) pdf_replay *= pdf;
    if (kf != 0u && float(i) >= RR_START_DEPTH) {
      vec3 beta = f_prefix / pdf_path;
      float survive = rr_survival(beta);
      if (rng_dim(key, dim_vertex(i) + DIM_RR) >= survive) break;
      pdf_path *= survive;
    }
    v = w;
  }
}

// The albedo control variate (docs/ARCHITECTURE.md, "The albedo control variate"): the albedo of a
// surface the camera sees, A = diffuse + f0 of its BSDF, 0 where the ray escapes.
vec3 cv_albedo(BsdfParams b) { return b.diffuse + b.f0; }

// What the camera sees at the pixel, averaged over G x G camera samples stratified over it, each
// with its own lens sample and time (random streams first_stream + s): the same distribution as the
// domain's camera sample, so the mean has the same expectation. `albedo`: the albedo of the surface
// seen (cv_albedo; 0 where the ray escapes); else what it sees emitting (x_1's emission, or the
// environment where the ray escapes).
vec3 stratified_mean(uvec2 pixel, uint index, uint g, uint first_stream, bool albedo) {
  vec3 sum = vec3(0.0);
  for (uint s = 0u; s < g * g; ++s) {
    CameraSample cs = camera_sample(frame_key(index, first_stream + s));
    cs.jitter = (vec2(float(s % g), float(s / g)) + cs.jitter) / float(g);
    vec3 origin;
    vec3 dir;
    primary_ray(camera_at(false, cs.time), vec2(pixel), cs.jitter, cs.lens, origin, dir);
    RayHit h;
    g_rays++;
    if (!trace_closest(origin, dir, RAY_UNBOUNDED, h)) {
      if (!albedo) sum += environment_radiance(dir);
      continue;
    }
    Vertex v = load_vertex(false, h, dir, camera_spread(false));
    sum += albedo ? cv_albedo(v.bsdf) : v.emission;
  }
  return sum / float(g * g);
}

// What the camera sees directly, by G x G stratified camera samples (G = direct_strata). Its mean is
// the same integral as the single camera ray's; stratification removes most of the variance at the
// edges of bright, directly visible surfaces (a pixel that sees a light over 2% of its area
// otherwise shows the whole light in 2% of its frames).
vec3 direct_emission(uvec2 pixel, uint index) {
  return stratified_mean(pixel, index, u_restir.direct_strata, RNG_STREAM_DIRECT_STRATA, false);
}

bool sees_emission(GpuPrimaryHit h) {
  if ((h.flags & PRIMARY_HIT) == 0u) return environment_emits();
  return (floatBitsToUint(h.shading_normal_kind.w) & SURFACE_KIND_EMISSIVE) != 0u;
}

vec3 primary_albedo(GpuPrimaryHit e, uint entry) {
  if ((e.flags & PRIMARY_HIT) == 0u) return vec3(0.0);
  SurfaceHit s = primary_surface_hit(false, e);
  return cv_albedo(fixed_primary_material(false, entry, s).bsdf);
}

// What this pixel's 8 neighbours' visibility-buffer entries say about the edges it may straddle,
// read in one pass over them. Only the neighbours, never this pixel's own camera sample, so the
// choices below leave every estimate of the pixel unbiased.
struct Edges {
  // Something the camera sees emitting (an emitter, or the environment between objects): some
  // neighbours see emission directly and some do not.
  bool emission;
  // An albedo edge on one surface: every neighbour sees a surface like the first one's
  // (centre_surface.glsl: kind, normal, distance), in more than one material. Silhouettes and
  // creases, where the lighting changes with the surface, are left out: there the pixel's earlier
  // radiance predicts little (the albedo control variate).
  bool albedo;
};

Edges neighbourhood_edges(uvec2 pixel) {
  bool seen = false;
  bool unseen = false;
  bool one_surface = true;
  bool differ = false;
  bool first = true;
  uint m0 = 0u;
  CentreSurface c0;
  for (int dy = -1; dy <= 1; ++dy) {
    for (int dx = -1; dx <= 1; ++dx) {
      ivec2 n = ivec2(pixel) + ivec2(dx, dy);
      if ((dx == 0 && dy == 0) || n.x < 0 || n.y < 0 || n.x >= int(u_frame.width) || n.y >= int(u_frame.height)) continue;
      GpuPrimaryHit e = b_primary[pixel_index(uvec2(n))];
      bool emits = sees_emission(e);
      seen = seen || emits;
      unseen = unseen || !emits;
      CentreSurface c = centre_surface(e);
      uint m = floatBitsToUint(e.geo_normal_material.w);
      if (first) {
        c0 = c;
        m0 = m;
        first = false;
      }
      one_surface = one_surface && c.valid && similar_surface(c0, c);
      differ = differ || m != m0;
    }
  }
  Edges edges;
  edges.emission = seen && unseen;
  edges.albedo = one_surface && differ;
  return edges;
}

// The mean albedo over G x G stratified camera samples (G = albedo_strata): its expectation is that
// of the primary vertex's albedo.
vec3 stratified_albedo(uvec2 pixel, uint index) {
  return stratified_mean(pixel, index, u_restir.albedo_strata, RNG_STREAM_ALBEDO_STRATA, true);
}

// The canonical reservoir: the selected candidate with its p-hat and W (RS-main Eq. 5) and
// confidence 1 (one domain's candidates), and f(Y) in `f`; empty, with confidence 1, where W is not
// positive. (The resampling passes' finalise_reservoir differs: they keep a selected sample whose W
// is 0, and their confidence is a sum.)
Reservoir canonical_reservoir(out vec3 f) {
  Reservoir r = g_selected;
  r.ucw = gris_ucw(g_state);  // RS-main Eq. 5
  r.p_hat = g_state.selected_p_hat;
  r.confidence = 1.0;
  f = g_selected_f;
  if (!(r.ucw > 0.0)) {
    r = reservoir_empty();
    r.confidence = 1.0;
    f = vec3(0.0);
  }
  return r;
}

// The canonical sample of one deep domain of the compacted list (SPEC_DOMAIN_LIST): the same
// estimator with its own random streams (keyed by the domain index) and the domain's depth range.
void deep_domain_main() {
  uint i = gl_WorkGroupID.x * DOMAIN_LIST_GROUP + gl_LocalInvocationIndex;
  if (i >= b_domain_args.count) return;
  uint domain = b_domain_list[i];
  uvec2 pixel = domain_pixel_of(domain);
  g_range = b_domains[domain];
  g_layer = domain_layer_of(domain);
  g_state = gris_begin();
  g_selected = reservoir_empty();
  g_selected_f = vec3(0.0);
  g_primary_emission = vec3(0.0);
  g_select_rng = frame_rng(domain, RNG_SALT_INITIAL_SELECT);
  float n_init = float(u_restir.initial_candidates);
  for (uint p = 0u; p < u_restir.initial_candidates; ++p)
    trace_candidates(pixel, frame_key(domain, RNG_STREAM_PATH_FIRST + p), n_init);
  vec3 f;
  Reservoir r = canonical_reservoir(f);
  store_output(domain, r, f, g_state.estimate);
  if (g_state.rejected > 0u) counter_add(COUNTER_NONFINITE_REJECTED, g_state.rejected);
  counter_add(COUNTER_RAYS_INITIAL, g_rays);
  counter_add(COUNTER_PATHS, u_restir.initial_candidates);
}

void main() {
  if (k_domain_list) {
    deep_domain_main();
    return;
  }
  uvec2 pixel = gl_GlobalInvocationID.xy;
  if (pixel.x >= u_frame.width || pixel.y >= u_frame.height) return;
  uint index = pixel_index(pixel);  // the random streams are per pixel
  uint domain = domain_of(pixel, 0u);
  g_state = gris_begin();
  g_selected = reservoir_empty();
  g_selected_f = vec3(0.0);
  g_primary_emission = vec3(0.0);
  g_select_rng = frame_rng(index, RNG_SALT_INITIAL_SELECT);
  uint candidates = initial_candidates_of(domain);
  float n_init = float(candidates);
  for (uint p = 0u; p < candidates; ++p)
    trace_candidates(pixel, frame_key(index, RNG_STREAM_PATH_FIRST + p), n_init);

  vec3 f;
  Reservoir r = canonical_reservoir(f);
  Edges edges;
  edges.emission = false;
  edges.albedo = false;
  if (u_restir.direct_strata > 1u || u_restir.albedo_strata > 0u) edges = neighbourhood_edges(pixel);
  if (u_restir.direct_strata > 1u && edges.emission) g_primary_emission = direct_emission(pixel, index);
  store_output(domain, r, f, g_state.estimate);  // the path's contributions summed, as pt's estimate
  b_contribution[primary_emission_index(pixel)] = vec4(g_primary_emission, 0.0);
  if (u_restir.colour_cv > 0.0) {
    // The colour control variate's B (restir_shade.comp): this estimate, kept apart from the later
    // passes' (store_output sanitized it), and an empty window mask for the spatial pass to fill.
    uint domains = domain_count();
    uint pixels = u_frame.width * u_frame.height;
    vec3 b = b_contribution[estimate_index(domain)].rgb;
    b_contribution[contribution_canonical_index(index, domains, pixels)] = vec4(b, uintBitsToFloat(0u));
  }
  if (u_restir.albedo_strata > 0u) {
    uint domains = domain_count();
    uint pixels = u_frame.width * u_frame.height;
    vec3 a1 = primary_albedo(b_primary[index], index);
    vec4 delta = vec4(0.0);
    if (edges.albedo) delta = vec4(stratified_albedo(pixel, index) - a1, 1.0);
    b_contribution[contribution_cv_delta_index(index, domains, pixels)] = delta;
    b_contribution[contribution_cv_albedo_index(index, domains, pixels)] = vec4(a1, 0.0);
  }
  if (g_state.rejected > 0u) counter_add(COUNTER_NONFINITE_REJECTED, g_state.rejected);
  counter_add(COUNTER_RAYS_INITIAL, g_rays);
  counter_add(COUNTER_PATHS, candidates);
}
