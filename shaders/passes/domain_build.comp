#version 460
// Pass `domain_build` (stage domain_init; ML 4.2, 4.3, Sec. 5): per pixel, the representative hits
// of its deep layers and the depth ranges of all its layers for this frame.
//   - How deep to look: the deepest layer that domain_propagate marked here or, for hole filling,
//     within hole_fill_radius pixels where the pixel lies within silhouette_band of a silhouette
//     (elsewhere a filled domain would be inactive); every layer with layer_mode uniform.
//   - The representative hits c_{p,i}: the pixel-centre ray (the primary stage's, whose first hit
//     is layer 0) walked on through its surfaces, front faces counted (restir/layer_data.h); each
//     is stored as the visibility-buffer entry of its domain, with its surface in this frame.
//   - The occluder check (ML Sec. 5, footnote 2): a marked deep domain is active when its own
//     immediate occluder (the instance of the layer in front) is one of the occluders the marks
//     carried; it then propagates to the next frame. (Hole filling is domain_fill's.)
//   - Depth ranges [(1-e)t, (1+e)t], where two adjacent ones overlap both clamped to the midpoint.
// The front layer's disocclusion (ML's disoccluded pixels, Table 1): its representative hit, moved
// back with its object, was hidden from the previous camera behind another surface (a closest-hit
// query in the previous frame's TLAS, as the evaluation's disocclusion mask tests it:
// render/disocclusion.h), or its object changed LoD level; not when it fell outside the previous image.
// Of those, the ones an active deep domain of the previous pixel they fall in held in its depth range
// are counted as held (the activation's coverage, ML Table 1's "Domain Effectiveness").
// With silhouette_band > 0, the front layer's silhouettes are flagged (DOMAIN_SILHOUETTE: a
// 4-neighbour's centre ray sees another instance, nothing, or a depth more than
// SILHOUETTE_DEPTH_RATIO apart), for domain_fill's silhouette band.
// With reveal_lookahead > 0, a deep domain whose hit and front hit both moved back into the previous
// image is predicted (DOMAIN_PREDICTED), and flagged DOMAIN_REVEALING when, both keeping the motion
// of the last frame, the front layer moves off it within reveal_lookahead frames: domain_fill lets
// only those sample (ours, not the ML paper's; docs/ARCHITECTURE.md, "Pixel layers").
// A census of about 1,024 pixels (every eighth in each direction at 256 x 256; the grid's offset
// moves each frame) walks all k layers, so that the frame reports how many deep domains a uniform
// k-layer scheme would keep (ML Table 1) without walking every pixel.
#extension GL_EXT_ray_query : require
#extension GL_GOOGLE_include_directive : require

layout(local_size_x = 8, local_size_y = 8, local_size_z = 1) in;

#define STRATA_HISTORY 1
#include "include/scene_bridge.glsl"
#include "restir/restir_pass.glsl"
#include "restir/layers.glsl"
#include "restir/centre_surface.glsl"

layout(set = 0, binding = BINDING_PRIMARY, std430) buffer Primary { GpuPrimaryHit b_primary[]; };
layout(set = 0, binding = BINDING_DOMAIN_MARKS, std430) readonly buffer Marks { GpuDomainMark b_marks[]; };
layout(set = 0, binding = BINDING_PRIMARY_PREV, std430) readonly buffer PrimaryPrev { GpuPrimaryHit b_primary_prev[]; };

#include "sampling/warp.h"
#include "include/camera.glsl"
#include "restir/projection.glsl"
#include "restir/seen_in_pixel.glsl"

// The uniform census: every s-th pixel in x and y, s such that about 1,024 pixels walk (8 at
// 256 x 256, every pixel up to 32 x 32), from an offset that moves each frame through all s * s.
uint census_stride() { return clamp(uint(sqrt(float(u_frame.width * u_frame.height) / 1024.0)), 1u, 8u); }

// Whether the front layer's hit was hidden from the previous camera behind another surface (or its
// object switched LoD level): one closest-hit query in the previous frame. A hit outside the
// previous image is not a disocclusion (ML Table 1 counts surfaces that were occluded: no layer of
// any scheme held a surface the previous camera did not look at); the evaluation's disocclusion
// mask (render/disocclusion.h) counts both, as every pixel without history.
// The ray is skipped where the point was seen in the previous pixel it falls in (seen_in_pixel).
// held: the point lay in the depth range of an active deep domain of the previous pixel it falls in
// (ML Table 1 "Domain Effectiveness": the activation's coverage, before any splat has to land).
// moved_back, xy: the point lay on the previous image, at xy (previous_screen_position's answer for
// the front hit, which the reveal prediction reuses).
bool disoccluded(GpuPrimaryHit front, inout uint rays, out bool held, out bool moved_back, out vec2 xy) {
  held = false;
  moved_back = false;
  xy = vec2(0.0);
  if ((u_frame.history_flags & HISTORY_VALID) == 0u) return false;
  ResolvedSurface before = resolve_surface(true, primary_surface(front));
  if (before.reason != RESOLVE_OK) return true;
  vec3 p = before.hit.position;  // in the previous frame's render space: its camera at the origin
  float dist = length(p);
  uvec2 q;
  vec2 sub;
  if (!(dist > 0.0) || !project(u_frame.prev_camera, u_frame.prev_width, u_frame.prev_height, p, vec3(0.0), q, sub)) return false;
  moved_back = true;
  xy = vec2(q) + sub;
  if (seen_in_pixel(true, q, front.instance, dist)) return false;
  RayHit h;
  rays++;
  if (!(trace_closest_in(true, vec3(0.0), p / dist, dist * (1.0 + LAYER_OCCLUDER_MARGIN), h) && h.t < dist * (1.0 - LAYER_OCCLUDER_MARGIN))) return false;
  uint layer = layer_by_range(true, q, dist);
  held = layer >= 1u && layer < u_restir.layers;
  return true;
}

bool marked(ivec2 q, uint layer) {
  return in_image(q) && b_marks[domain_of(uvec2(q), layer)].occluder_min != OCCLUDER_NONE;
}

bool silhouette(uvec2 pixel, GpuPrimaryHit front) {
  const ivec2 steps[4] = ivec2[4](ivec2(1, 0), ivec2(-1, 0), ivec2(0, 1), ivec2(0, -1));
  for (uint j = 0u; j < 4u; ++j) {
    ivec2 q = ivec2(pixel) + steps[j];
    if (!in_image(q)) continue;
    GpuPrimaryHit n = b_primary[domain_of(uvec2(q), 0u)];
    if ((n.flags & PRIMARY_HIT) == 0u || n.instance != front.instance ||
        abs(n.t - front.t) > SILHOUETTE_DEPTH_RATIO * min(n.t, front.t))
      return true;
  }
  return false;
}

// Whether a front-layer silhouette (DOMAIN_SILHOUETTE, as main sets it) lies within silhouette_band
// pixels: domain_fill's test, read here from the primary hits, which this pass does not write.
bool near_silhouette(uvec2 pixel) {
  int r = int(u_restir.silhouette_band);
  for (int dy = -r; dy <= r; ++dy)
    for (int dx = -r; dx <= r; ++dx) {
      ivec2 q = ivec2(pixel) + ivec2(dx, dy);
      if (dx * dx + dy * dy > r * r || !in_image(q)) continue;
      GpuPrimaryHit n = b_primary[domain_of(uvec2(q), 0u)];
      if ((n.flags & PRIMARY_HIT) != 0u && silhouette(uvec2(q), n)) return true;
    }
  return false;
}

// The deepest layer this pixel must find: marked here (the occluder check decides whether it is
// active or dormant, and a dormant one keeps propagating), or, for hole filling, marked within
// hole_fill_radius pixels. With the silhouette band, a hole-filled domain farther than the band
// from every silhouette is inactive (domain_fill), so its representative hit would go unused: such
// a pixel walks for its own marks only.
uint deepest_needed(uvec2 pixel) {
  int r = int(u_restir.hole_fill_radius);
  int near = u_restir.silhouette_band == 0u ? 1 : -1;  // a silhouette within the band, once asked
  for (uint i = u_restir.layers - 1u; i >= 1u; --i) {
    if (marked(ivec2(pixel), i)) return i;
    if (r == 0 || near == 0) continue;
    bool fill = false;
    for (int dy = -r; dy <= r && !fill; ++dy)
      for (int dx = -r; dx <= r && !fill; ++dx)
        fill = dx * dx + dy * dy <= r * r && marked(ivec2(pixel) + ivec2(dx, dy), i);
    if (!fill) continue;
    if (near < 0) near = near_silhouette(pixel) ? 1 : 0;
    if (near == 1) return i;
  }
  return 0u;
}

// The reveal prediction (reveal_lookahead > 0; ours, not the ML paper's): where a hit of this
// frame's pixel-centre ray lay on the previous frame's image, its surface moved back by the resolver.
bool previous_screen_position(GpuPrimaryHit e, out vec2 xy) {
  xy = vec2(0.0);
  if ((u_frame.history_flags & HISTORY_VALID) == 0u) return false;
  ResolvedSurface before = resolve_surface(true, primary_surface(e));
  if (before.reason != RESOLVE_OK) return false;
  uvec2 q;
  vec2 sub;
  if (!project(u_frame.prev_camera, u_frame.prev_width, u_frame.prev_height, before.hit.position, vec3(0.0), q, sub)) return false;
  xy = vec2(q) + sub;
  return true;
}

const uint REVEAL_STEPS_MAX = 32u;  // front-layer pixels read along one prediction

// Whether a deep hit at camera distance t, which moves by `relative` pixels a frame against the
// front layer of its pixel, comes out from behind it within reveal_lookahead frames: after s frames
// it lies under what is now at pixel + s * relative, and it is uncovered when the front layer there
// is missing or no nearer than it (SILHOUETTE_DEPTH_RATIO, as the silhouettes' test). The path is
// read in steps of at most one pixel (REVEAL_STEPS_MAX at most); one that leaves the image counts as
// revealing (what lies beyond is unknown).
bool revealing(uvec2 pixel, vec2 relative, float t) {
  float frames = float(u_restir.reveal_lookahead);
  uint steps = min(uint(ceil(length(relative) * frames)), REVEAL_STEPS_MAX);
  for (uint j = 1u; j <= steps; ++j) {
    ivec2 q = ivec2(floor(vec2(pixel) + 0.5 + relative * (frames * float(j) / float(steps))));
    if (!in_image(q)) return true;
    GpuPrimaryHit f = b_primary[domain_of(uvec2(q), 0u)];
    if ((f.flags & PRIMARY_HIT) == 0u || f.t > t * (1.0 - SILHOUETTE_DEPTH_RATIO)) return true;
  }
  return false;
}

GpuPrimaryHit entry_of(RayHit h, float t, SurfaceHit s) {
  GpuPrimaryHit p;
  p.t = t;
  p.instance = h.instance;
  p.geometry = h.geometry;
  p.triangle = h.triangle;
  p.bary = h.bary;
  p.lod = instance_in(false, h.instance).lod;
  p.flags = PRIMARY_HIT;
  p.jitter = vec2(0.5);
  p.lens = packUnorm2x16(vec2(0.5));
  p.time = 1.0;
  p.position_area = vec4(s.position, s.area);
  p.geo_normal_material = vec4(s.geo_normal, uintBitsToFloat(s.material));
  SurfaceMaterial m = material_at(s, primary_footprint(camera_spread(false), s.position, dot(s.geo_normal, normalize(s.position))));
  p.shading_normal_kind = vec4(s.shading_normal, uintBitsToFloat(surface_kind(m)));
  return p;
}

void main() {
  uvec2 pixel = gl_GlobalInvocationID.xy;
  if (pixel.x >= u_frame.width || pixel.y >= u_frame.height) return;
  uint k = u_restir.layers;
  bool uniform_mode = u_restir.layer_mode == LAYER_MODE_UNIFORM;
  uint stride = census_stride();
  uvec2 census_offset = uvec2(u_frame.frame_index % stride, (u_frame.frame_index / stride) % stride);
  bool census = uniform_mode || all(equal(pixel % stride, census_offset));
  GpuPrimaryHit front = b_primary[domain_of(pixel, 0u)];
  bool front_hit = (front.flags & PRIMARY_HIT) != 0u;
  uint own = front_hit && !uniform_mode ? deepest_needed(pixel) : 0u;  // the deepest layer this pixel's domains need
  uint needed = front_hit && (uniform_mode || census) ? k - 1u : own;

  float t_of[LAYERS_MAX];
  uint occluder_of[LAYERS_MAX];
  uint found = front_hit ? 1u : 0u;  // layers with a representative hit (0 .. found-1)
  t_of[0] = front.t;
  occluder_of[0] = OCCLUDER_NONE;
  uint rays = 0u;
  if (needed > 0u) {
    vec3 origin;
    vec3 dir;
    primary_ray(u_frame.camera, vec2(pixel), vec2(0.5), vec2(0.5), origin, dir);  // the primary stage's centre ray
    float t0 = step_beyond(front.t);
    uint last = front.instance;
    for (uint step = 0u; step < 2u * LAYERS_MAX && found <= needed; ++step) {
      RayHit h;
      rays++;
      if (!trace_closest(origin + dir * t0, dir, RAY_UNBOUNDED, h)) break;
      float t = t0 + h.t;
      SurfaceHit s = load_hit(h);
      if (dot(s.geo_normal, dir) < 0.0) {  // a front face: the next layer's representative hit
        b_primary[domain_of(pixel, found)] = entry_of(h, t, s);
        t_of[found] = t;
        occluder_of[found] = last;
        last = h.instance;
        found++;
      }
      t0 = step_beyond(t);
    }
  }
  bool held = false;
  bool front_moved_back = false;
  vec2 front_before;
  bool front_disoccluded = front_hit && disoccluded(front, rays, held, front_moved_back, front_before);
  if (front_disoccluded) counter_add(COUNTER_DISOCCLUDED, 1u);
  if (held) counter_add(COUNTER_DISOCCLUDED_HELD, 1u);
  counter_add(COUNTER_RAYS_DOMAIN_INIT, rays);
  if (census && found > 1u) counter_add(COUNTER_DOMAINS_UNIFORM, (found - 1u) * (uniform_mode ? 1u : stride * stride));
  // A census pixel walks deeper than its domains need: the layers beyond are counted only, so that
  // its domains (hits, ranges, activation) are what any other pixel's would be.
  if (!uniform_mode) found = min(found, own + 1u);

  // The reveal prediction: every hit found lies on the pixel-centre ray, so the motion of deep hit i
  // against the front hit over the last frame is the difference of their previous positions.
  bool predict = u_restir.reveal_lookahead > 0u && !uniform_mode && found > 1u && front_moved_back;
  // Depth ranges (ML Sec. 5): [(1-e)t, (1+e)t], overlapping neighbours clamped to their midpoint.
  float e = u_restir.depth_range_epsilon;
  float lo[LAYERS_MAX];
  float hi[LAYERS_MAX];
  for (uint i = 0u; i < found; ++i) {
    lo[i] = (1.0 - e) * t_of[i];
    hi[i] = (1.0 + e) * t_of[i];
  }
  for (uint i = 0u; i + 1u < found; ++i) {
    if (hi[i] > lo[i + 1u]) {
      float m = 0.5 * (hi[i] + lo[i + 1u]);
      hi[i] = m;
      lo[i + 1u] = m;
    }
  }
  for (uint i = 0u; i < k; ++i) {
    uint d = domain_of(pixel, i);
    GpuDomainRange r;
    r.range_min = i < found ? lo[i] : 0.0;
    r.range_max = i < found ? hi[i] : 0.0;
    r.occluder = i < found ? occluder_of[i] : OCCLUDER_NONE;
    r.flags = 0u;
    if (i < found) {
      r.flags = DOMAIN_HIT;
      if (i == 0u || uniform_mode) {
        r.flags |= DOMAIN_ACTIVE | DOMAIN_PROPAGATES;  // front layer: always; uniform: every layer
        if (i == 0u && front_disoccluded) r.flags |= DOMAIN_DISOCCLUDED | (held ? DOMAIN_HELD : 0u);
        if (i == 0u && u_restir.silhouette_band > 0u && silhouette(pixel, front)) r.flags |= DOMAIN_SILHOUETTE;
      } else {
        vec2 before;
        if (predict && previous_screen_position(b_primary[d], before))
          r.flags |= DOMAIN_PREDICTED | (revealing(pixel, front_before - before, t_of[i]) ? DOMAIN_REVEALING : 0u);
        GpuDomainMark m = b_marks[d];
        if (m.occluder_min != OCCLUDER_NONE) {
          // ML Sec. 5: activated only when the propagated hit's occluder is this hit's occluder.
          if (r.occluder == m.occluder_min || r.occluder == ~m.occluder_max) r.flags |= DOMAIN_ACTIVE | DOMAIN_PROPAGATES;
          else counter_add(COUNTER_DOMAINS_OCCLUDER, 1u);
        }
      }
    } else if (i > 0u) {
      b_primary[d].flags = 0u;  // no representative hit this frame
    }
    b_domains[d] = r;
  }
}
