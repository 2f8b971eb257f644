// The temporal passes' history (restir_temporal.comp and restir_temporal_reverse.comp, which find
// the same history pixel q for a pixel from the same visibility buffers): the current pixel-centre
// hit backprojected into the previous frame, and the history filter's search around it. `count`:
// this call counts the LoD mappings of the backprojection (one of the two passes does).
// Needs: the scene bridge with STRATA_HISTORY, restir/restir_pass.glsl, restir/centre_surface.glsl,
// and the pass's b_primary and b_primary_prev.
#ifndef STRATA_TEMPORAL_HISTORY_GLSL
#define STRATA_TEMPORAL_HISTORY_GLSL

uint g_rays = 0u;  // this invocation's rays, added to COUNTER_RAYS_TEMPORAL at its end

// Counts a temporal shift (either pass's) and its rays.
void count_shift(ShiftResult s) {
  g_rays += s.rays;
  counter_add(COUNTER_TEMPORAL_SHIFTS, 1u);
  if (s.reason != SHIFT_OK) counter_add(COUNTER_TEMPORAL_FAIL + s.reason, 1u);
  count_suffix(s, COUNTER_RAYS_REPLAY);
}

// Backprojection: the previous pixel q that saw this pixel's centre hit (the primary stage's
// visibility buffer) moved back with its object's previous transform, through the previous camera.
// For the biased option's validation also q's own centre hit in frame t-1 (load_previous_centre):
// the previous G-buffer sample the DI tutorial validates against, from the previous visibility buffer.
struct Backprojection {
  uvec2 q;                 // the history pixel: under s, or the one the history search chose
  vec2 s;                  // the backprojected position in the previous image (pixels)
  SurfaceHit centre;       // this pixel's centre hit, frame t
  ResolvedSurface before;  // its surface point in frame t-1 (render space of t-1: the previous camera at the origin)
  bool have_previous;      // q's centre ray hit something in frame t-1
  SurfaceHit previous;     // q's centre hit, frame t-1 (render space of t-1)
};

// The t-th previous pixel tried around the backprojected one (offset from it), nearest first:
// itself, its neighbours on the sides nearer to the backprojected position (along the nearer axis
// first), the diagonal between them, then the far sides and corners.
ivec2 temporal_try_offset(uint t, ivec2 step, bool x_first) {
  ivec2 a = x_first ? ivec2(step.x, 0) : ivec2(0, step.y);  // the nearer side
  ivec2 b = x_first ? ivec2(0, step.y) : ivec2(step.x, 0);
  const ivec2 order[9] = ivec2[9](ivec2(0), a, b, a + b, -a, -b, -a + b, a - b, -a - b);
  return order[min(t, 8u)];
}

bool backproject(uvec2 pixel, bool count, out Backprojection b) {
  b.have_previous = false;
  GpuPrimaryHit entry = b_primary[pixel_index(pixel)];
  SurfacePoint centre = primary_surface(entry);
  if (centre.instance == SURFACE_NONE) return false;
  b.centre = primary_surface_hit(false, entry);
  b.before = resolve_surface(true, centre);  // across a LoD switch: tau of the centre (LOD 4.4's motion vectors)
  if (count) count_lod_mapping(b.before);
  if (b.before.reason != RESOLVE_OK) return false;
  vec3 ndc = camera_ndc(u_frame.prev_camera, b.before.hit.position);
  if (!(ndc.z > 0.0)) return false;
  vec2 s = vec2((ndc.x + 1.0) * 0.5 * float(u_frame.prev_width), (1.0 - ndc.y) * 0.5 * float(u_frame.prev_height));
  if (!(s.x >= 0.0 && s.y >= 0.0 && s.x < float(u_frame.prev_width) && s.y < float(u_frame.prev_height))) return false;
  b.q = uvec2(s);
  b.s = s;
  return true;
}

// The history filter and search: whether q's centre surface in frame t-1 is like this pixel's
// centre surface moved back to frame t-1 (both at their distance from the previous camera); when it
// is not (its camera sample of frame t-1 found a blade or an edge that this pixel's does not), the
// other previous pixels around s are tried, nearest first (RESTIR_TEMPORAL_TRIES), and the first
// that is becomes q. Reads the visibility buffers only, never a reservoir, so the domain is still
// chosen independently of the samples.
bool find_history(inout Backprojection b) {
  CentreSurface now = surface_of(b.before, length(b.before.hit.position), camera_spread(true));
  vec2 f = fract(b.s);
  ivec2 step = ivec2(f.x < 0.5 ? -1 : 1, f.y < 0.5 ? -1 : 1);  // towards the nearer neighbours
  bool x_first = abs(f.x - 0.5) > abs(f.y - 0.5);
  for (uint t = 0u; t < RESTIR_TEMPORAL_TRIES; ++t) {
    ivec2 c = ivec2(uvec2(b.s)) + temporal_try_offset(t, step, x_first);
    if (c.x < 0 || c.y < 0 || c.x >= int(u_frame.prev_width) || c.y >= int(u_frame.prev_height)) continue;
    if (similar_surface(now, centre_surface(b_primary_prev[uint(c.y) * u_frame.prev_width + uint(c.x)]))) {
      b.q = uvec2(c);
      return true;
    }
  }
  return false;
}

void load_previous_centre(inout Backprojection b) {
  GpuPrimaryHit q_entry = b_primary_prev[b.q.y * u_frame.prev_width + b.q.x];
  b.have_previous = (q_entry.flags & PRIMARY_HIT) != 0u;
  if (b.have_previous) b.previous = primary_surface_hit(true, q_entry);
}

// Step 1, find the history: the previous pixel q whose reservoir is this pixel's history
// (backprojection, then the history filter's search), chosen from geometry alone; false when there
// is none. Whether domain q takes part depends on geometry only. An empty reservoir in q still
// claims its MIS share of the canonical sample (its confidence counts), it just brings no
// candidate. With the history filter, q takes part only when its centre surface is like this
// pixel's (find_history): a pixel that was disoccluded has no history, instead of the occluder's.
bool find_temporal_neighbor(uvec2 pixel, bool unbiased, bool count, out Backprojection bp) {
  bool have_history = backproject(pixel, count, bp);
  if (have_history && (u_restir.flags & RESTIR_TEMPORAL_FILTER) != 0u) have_history = find_history(bp);
  if (have_history && !unbiased) load_previous_centre(bp);  // the biased validation's, of the final q
  return have_history;
}

#endif
