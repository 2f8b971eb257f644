#version 460
// Pass `spatial` (stage spatial; Lin et al. 2022 section 7): N neighbours in a disk of
// `spatial_radius` pixels, chosen independently of the samples, are shifted into this pixel and
// resampled with its own reservoir. A candidate neighbour whose pixel-centre surface (the primary
// stage's visibility buffer) differs from this pixel's in normal, depth or material kind is refused
// and another is drawn, up to RESTIR_SPATIAL_TRIES per slot (docs/ARCHITECTURE.md, "Spatial
// neighbours"): the choice of domains depends on geometry only, never on a reservoir, so the MIS
// weights below still sum to one over the chosen domains and the estimate stays unbiased. MIS is either the generalized balance heuristic over all
// N + 1 domains (RS-main Eq. 6/7; every candidate is shifted into every other domain: O(N^2)
// shifts) or confidence-weighted pairwise MIS (restir/gris.h; O(N) shifts). With pairwise MIS the
// first neighbours are the frame's pairs (restir/spatial_pairs.glsl): their shifts both ways were
// made once by restir_spatial_pairs.comp, and only the neighbours drawn at random are shifted here.
#extension GL_EXT_ray_query : require
#extension GL_GOOGLE_include_directive : require

layout(local_size_x = 8, local_size_y = 8, local_size_z = 1) in;

#include "include/scene_bridge.glsl"
#include "restir/restir_pass.glsl"
#include "restir/path_space.glsl"
#include "restir/restir_limits.h"
#include "restir/thresholds.h"
#include "restir/centre_surface.glsl"
#include "restir/layer_data.h"
#include "restir/spatial_pair_data.h"

layout(set = 0, binding = BINDING_RESERVOIRS_IN, std430) readonly buffer ReservoirsIn { PackedReservoir b_in[]; };
layout(set = 0, binding = BINDING_PRIMARY, std430) readonly buffer Primary { GpuPrimaryHit b_primary[]; };
layout(set = 0, binding = BINDING_DOMAINS, std430) readonly buffer Domains { GpuDomainRange b_domains[]; };  // restir-multilayer
// Pixels that draw neighbours at random (without pairs: those without history, which take
// disocclusion_spatial_neighbors; with pairs: every pixel whose pair does not fill its count) trace
// rays here. Run among the others, one such pixel holds up every lane of its SIMD group (lavapipe
// runs 8 pixels in lock-step, a GPU 32), so with k_compact the image dispatch only lists them, and a
// second, indirect dispatch runs the list densely. A pixel's result is the same either way:
// its random streams are keyed by the pixel. The same pipeline runs both dispatches (u_dispatch.list).
layout(constant_id = SPEC_SPATIAL_COMPACT) const bool k_compact = false;
layout(push_constant) uniform Dispatch { SpatialDispatch u_dispatch; };
layout(set = 0, binding = BINDING_SPATIAL_LIST, std430) buffer SpatialList { uint b_list[]; };
// x, y, z: the list dispatch's workgroups (y = z = 1, set by the host); w: the list's length.
layout(set = 0, binding = BINDING_SPATIAL_ARGS, std430) buffer SpatialArgs { uvec4 b_args; };

#include "restir/spatial_pairs.glsl"

uint g_rays = 0u;
const uint NO_PAIR = 0xFFFFFFFFu;

// The capped confidence of reservoir r of domain `domain` (this frame; restir_pass.glsl).
float confidence_of(Reservoir r, uint domain) {
  return confidence_capped(r.confidence, confidence_cap_of(b_primary[pixel_index(domain_pixel(domain, u_frame.width))]));
}

// Step 1, find the neighbours: the domains whose reservoirs this pixel resamples, chosen from the
// visibility buffer alone (never a reservoir), with their capped confidences.
struct SpatialNeighbours {
  uint count;
  uint filtered;                                    // candidates the surface filter refused
  uint domain[RESTIR_MAX_SPATIAL_NEIGHBORS];
  uint pair_slot[RESTIR_MAX_SPATIAL_NEIGHBORS];     // the pair slot of a paired neighbour, else NO_PAIR
  float confidence[RESTIR_MAX_SPATIAL_NEIGHBORS];   // capped, read once (find_confidences)
};

// The pairs first: i + o_m and i - o_m where the surfaces are alike both ways.
void find_pair_neighbours(uvec2 pixel, CentreSurface here, ivec2 o_pair[SPATIAL_MAX_PAIR_OFFSETS], uint slots,
                          inout SpatialNeighbours n) {
  for (uint s = 0u; s < pair_slots() && n.count < slots; ++s) {
    ivec2 p = ivec2(pixel) + pair_direction(o_pair, s);
    if (!in_image(p)) continue;
    if (similar_pair(here, centre_surface(b_primary[pixel_index(uvec2(p))]))) {
      n.domain[n.count] = domain_of(uvec2(p), 0u);
      n.pair_slot[n.count] = s;
      n.count++;
    } else {
      n.filtered++;
    }
  }
}

// The other neighbours: uniform in the disk, rounded to pixels, inside the image, not this pixel
// nor one of its pairs, and seeing a surface like this pixel's; each slot draws up to
// RESTIR_SPATIAL_TRIES candidates. A pixel that sees no surface has no path to reuse into and
// takes no neighbours.
void draw_neighbours(uvec2 pixel, CentreSurface here, ivec2 o_pair[SPATIAL_MAX_PAIR_OFFSETS], uint slots,
                     inout Rng rng, inout SpatialNeighbours n) {
  for (uint j = n.count; j < slots; ++j) {
    for (uint t = 0u; t < RESTIR_SPATIAL_TRIES; ++t) {
      vec2 o = sample_concentric_disk(rng_next_float2(rng)) * u_restir.spatial_radius;
      ivec2 d = ivec2(round(o));
      ivec2 p = ivec2(pixel) + d;
      if (!in_image(p) || p == ivec2(pixel)) continue;
      bool paired = false;
      for (uint m = 0u; m < min(k_pair_offsets, SPATIAL_MAX_PAIR_OFFSETS); ++m) paired = paired || d == o_pair[m] || d == -o_pair[m];
      if (paired) continue;
      if (!similar_surface(here, centre_surface(b_primary[pixel_index(uvec2(p))]))) {
        n.filtered++;
        continue;
      }
      n.domain[n.count] = domain_of(uvec2(p), 0u);
      n.pair_slot[n.count] = NO_PAIR;
      n.count++;
      break;
    }
  }
}

// The colour control variate (restir_shade.comp) must not take its colour from a pixel whose
// reservoir this one reuses: mark the neighbours inside its window.
void mark_colour_window(uvec2 pixel, SpatialNeighbours n) {
  uint mask = 0u;
  for (uint j = 0u; j < n.count; ++j) {
    ivec2 d = ivec2(domain_pixel(n.domain[j], u_frame.width)) - ivec2(pixel);
    if (max(abs(d.x), abs(d.y)) <= COLOUR_CV_RADIUS) mask |= 1u << colour_cv_window_bit(d);
  }
  uint pixels = u_frame.width * u_frame.height;
  b_contribution[contribution_canonical_index(pixel_index(pixel), pixels * u_restir.layers, pixels)].w = uintBitsToFloat(mask);
}

void main() {
  uvec2 pixel = gl_GlobalInvocationID.xy;
  const bool list = u_dispatch.list != 0u;
  if (list) {
    uint item = gl_WorkGroupID.x * (gl_WorkGroupSize.x * gl_WorkGroupSize.y) + gl_LocalInvocationIndex;
    if (item >= b_args.w) return;
    pixel = uvec2(b_list[item] % u_frame.width, b_list[item] / u_frame.width);
  }
  if (pixel.x >= u_frame.width || pixel.y >= u_frame.height) return;
  uint index = domain_of(pixel, 0u);  // spatial reuse is on the front layer
  Reservoir centre = unpack_reservoir(b_in[index]);
  vec3 f_centre = b_contribution[index].rgb;
  bool centre_valid = reservoir_valid(centre);
  float c_c = confidence_capped(centre.confidence, confidence_cap_of(b_primary[pixel_index(pixel)]));
  // restir-multilayer: a front-layer pixel whose hit the previous camera did not see (domain_build's
  // DOMAIN_DISOCCLUDED) counts as one without history even where a deep domain's splat reached it:
  // that history is capped like any other, so the pixel keeps the disocclusion boost that
  // restir-splat gives it, and the deep history comes on top (ML Fig. 9 compares the two).
  bool no_history = centre.confidence < 1.5 || (u_restir.layers > 1u && (b_domains[index].flags & DOMAIN_DISOCCLUDED) != 0u);
  // A pixel whose surface switched LoD level this frame keeps the boost too, where tau carried its
  // history across the switch: history resampled for the other level's targets (LOD 4.4).
  GpuPrimaryHit own = b_primary[pixel_index(pixel)];
  if ((own.flags & PRIMARY_HIT) != 0u && (instance_changes(own.instance) & INSTANCE_CHANGED_LOD) != 0u) no_history = true;
  CentreSurface here = centre_surface(own);
  // A pixel whose reservoir holds no history (disoccluded, or the first frame: its confidence is the
  // canonical sample's alone) takes disocclusion_spatial_neighbors. Confidence and the disocclusion
  // flag depend on geometry only (backprojection, the neighbour filter, the previous camera's view),
  // never on a sample, so the choice of domains stays independent of the samples.
  uint wanted = u_restir.spatial_neighbors;
  if (no_history && u_restir.disocclusion_spatial_neighbors > 0u) wanted = u_restir.disocclusion_spatial_neighbors;
  uint slots = here.valid ? min(wanted, RESTIR_MAX_SPATIAL_NEIGHBORS) : 0u;

  // 1. Find the neighbours.
  SpatialNeighbours nbs;
  nbs.count = 0u;
  nbs.filtered = 0u;
  float c_total = c_c;
  bool pairs = k_pair_offsets > 0u;
  ivec2 o_pair[SPATIAL_MAX_PAIR_OFFSETS];
  spatial_pair_offsets(o_pair);
  find_pair_neighbours(pixel, here, o_pair, slots, nbs);
  bool list_it = pairs ? nbs.count < slots : no_history;
  if (k_compact && !list && list_it && (b_primary[pixel_index(pixel)].flags & PRIMARY_HIT) != 0u) {
    uint item = atomicAdd(b_args.w, 1u);
    b_list[item] = pixel_index(pixel);
    atomicMax(b_args.x, item / (gl_WorkGroupSize.x * gl_WorkGroupSize.y) + 1u);
    return;
  }
  Rng rng = frame_rng(pixel_index(pixel), RNG_SALT_SPATIAL);  // the draws, then the selection
  draw_neighbours(pixel, here, o_pair, slots, rng, nbs);
  uint count = nbs.count;
  for (uint j = 0u; j < count; ++j) {
    nbs.confidence[j] = confidence_of(unpack_reservoir(b_in[nbs.domain[j]]), nbs.domain[j]);
    c_total += nbs.confidence[j];
  }
  if (nbs.filtered > 0u) counter_add(COUNTER_SPATIAL_FILTERED, nbs.filtered);
  if (u_restir.colour_cv > 0.0) mark_colour_window(pixel, nbs);

  // 2-4. Shift, MIS weights, stream.
  float k = float(count);
  bool pairwise = u_restir.mis_mode == MIS_PAIRWISE;

  // Shifts are jobs of one loop with a single call of shift_path (lavapipe compiles every inlined
  // call site separately). Per neighbour j, a block of jobs:
  //   0: y_j into this pixel (y'_j);
  //   1 .. count-1 (balance only): y'_j into each other neighbour domain l (p-hat-from of l);
  //   last: the centre sample into j's domain (for the centre's MIS weight).
  uint block = pairwise ? 2u : count + 1u;
  GrisState st = gris_begin();
  float m_c = pairwise ? 0.0 : 1.0;
  float balance_c = c_c * centre.p_hat;  // balance: denominator of the centre's weight
  Reservoir rj = reservoir_empty();
  PathSample yj_here = rj.y;
  vec3 fj = vec3(0.0);
  float p_here = 0.0;
  float jac = 0.0;
  float denom = 0.0;  // balance: denominator of y'_j's weight
  Reservoir selected = centre;
  vec3 f_selected = f_centre;
  bool took_neighbour = false;
  for (uint job = 0u; job < count * block; ++job) {
    uint j = job / block;
    uint sub = job % block;
    bool centre_job = sub == block - 1u;
    if (sub == 0u) {
      rj = unpack_reservoir(b_in[nbs.domain[j]]);
      rj.confidence = nbs.confidence[j];
      p_here = 0.0;
      jac = 0.0;
    }
    // What to shift where; jobs whose input is absent are skipped.
    uint target = nbs.domain[j];
    float c_target = 0.0;  // balance jobs: the confidence of neighbour domain l
    PathSample y = rj.y;
    bool run = reservoir_valid(rj);
    if (centre_job) {
      y = centre.y;
      run = centre_valid;
    } else if (sub > 0u) {
      uint l = sub - 1u < j ? sub - 1u : sub;  // the other neighbours, skipping j
      target = nbs.domain[l];
      c_target = nbs.confidence[l];
      y = yj_here;
      run = jac > 0.0;
    } else {
      target = index;
    }
    ShiftResult res;
    res.reason = SHIFT_FAIL_ZERO;
    uvec2 tp = domain_pixel(target, u_frame.width);
    if (run && pairs && nbs.pair_slot[j] != NO_PAIR) {
      // A paired neighbour: y_j into this pixel is this pixel's record of j's slot; the centre
      // sample into j is j's record of the opposite slot (restir_spatial_pairs.comp).
      uint slot = nbs.pair_slot[j];
      uvec2 at = centre_job ? domain_pixel(nbs.domain[j], u_frame.width) : pixel;
      res = load_pair(at, centre_job ? slot ^ 1u : slot, shift_camera(domain_primary(b_primary[pixel_index(at)], pixel_index(at)), y));
    } else if (run) {
      res = shift_path(false, vec2(tp), domain_primary(b_primary[pixel_index(tp)], pixel_index(tp)), y, false);
      g_rays += res.rays;
      counter_add(COUNTER_SPATIAL_SHIFTS, 1u);
      if (res.reason != SHIFT_OK) counter_add(COUNTER_SPATIAL_FAIL + res.reason, 1u);
    }
    bool ok = run && res.reason == SHIFT_OK;
    if (sub == 0u) {
      p_here = ok ? luminance(res.f) : 0.0;
      jac = ok ? res.jacobian : 0.0;
      yj_here = rj.y;
      yj_here.x1 = res.x1;
      yj_here.jitter = res.camera.jitter;
      yj_here.lens = res.camera.lens;
      yj_here.time = res.camera.time;
      yj_here.density = res.density;
      fj = res.f;
      denom = jac > 0.0 ? c_c * p_here + rj.confidence * rj.p_hat / jac : 0.0;
    } else if (!centre_job) {
      // Balance: p-hat of domain l from y'_j (RS-main Eq. 7).
      if (ok) denom += c_target * p_hat_from(luminance(res.f), res.jacobian);
    }
    if (centre_job) {
      float from_c = ok ? p_hat_from(luminance(res.f), res.jacobian) : 0.0;
      if (pairwise) m_c += mis_pairwise_canonical_term(rj.confidence, from_c, c_c, centre.p_hat, k, c_total);
      else balance_c += rj.confidence * from_c;
      // y'_j is complete: stream it (RS-main Eq. 4, w = m p-hat W |J|).
      float m = 0.0;
      if (jac > 0.0 && p_here > 0.0) {
        float from_j = rj.p_hat / jac;  // p-hat_j(y_j) |dy_j/dy'_j| (RS-main Eq. 7)
        m = pairwise ? mis_pairwise_neighbor(rj.confidence, from_j, c_c, p_here, k, c_total)
                     : (denom > 0.0 ? rj.confidence * from_j / denom : 0.0);
      }
      if (gris_stream_path(st, m * p_here * rj.ucw * jac, p_here, fj, rj.confidence, j + 1u, rng_next_float(rng))) {
        selected = rj;
        selected.y = yj_here;
        f_selected = fj;
        took_neighbour = true;
      }
    }
  }
  if (!pairwise) m_c = balance_c > 0.0 ? c_c * centre.p_hat / balance_c : 0.0;
  if (count == 0u) m_c = 1.0;
  if (gris_stream_path(st, m_c * centre.p_hat * centre.ucw, centre.p_hat, f_centre, c_c, 0u, rng_next_float(rng))) {
    selected = centre;
    f_selected = f_centre;
    took_neighbour = false;
  }

  if (took_neighbour) counter_add(COUNTER_SPATIAL_SELECTED, 1u);

  // 5. Finalise.
  finalise_reservoir(index, st, selected, f_selected, st.confidence);
  counter_add(COUNTER_RAYS_SPATIAL, g_rays);
}
