// Path vertices as both the candidate generator (restir_initial) and the shifts (path_space.glsl)
// see them, so that both apply exactly the same rules: the scattering function, the light densities
// of each frame, the technique MIS weight and the reconnectability rules (restir/reconnection.h).
// Needs: the scene bridge and the library context (restir/context.glsl).
#ifndef STRATA_PATH_VERTEX_GLSL
#define STRATA_PATH_VERTEX_GLSL

#include "material/bsdf.h"
#include "restir/reconnection.h"
#include "sampling/emitter_pdf.h"
#include "restir/reservoir.h"
#include "sampling/rng.h"
#include "restir/thresholds.h"
#include "sampling/mis.h"
#include "sampling/ray_offset.h"
#include "sampling/warp.h"
#include "include/camera.glsl"
#include "restir/camera_sample.glsl"

// Random-number dimensions of a path (rng_dim): the camera sample (restir/camera_sample.glsl),
// then a block per vertex x_i.
const uint DIM_BSDF = 0u;    // within a vertex block: 3 dimensions
const uint DIM_RR = 3u;      // Russian roulette
const uint DIM_NEE = 4u;     // 3 dimensions per light candidate
uint dim_vertex(uint i) { return 8u + 128u * i; }

struct Vertex {
  vec3 position;      // render space of the frame it was loaded in
  vec3 ng;            // geometric normal, on the side the path arrives from
  vec3 ns;            // shading normal, same side
  vec3 t;
  vec3 b;
  vec3 wo;            // local direction back along the arriving segment
  BsdfParams bsdf;
  bool rough;         // may take part in a reconnection (RECONNECT_MIN_ALPHA, or no specular lobe)
  vec3 emission;      // radiance emitted back along the arriving segment (0 when it faces away)
  vec3 material_emission;  // what light sampling selects its triangle by (SurfaceMaterial::light_emission)
  bool double_sided;
  float area;
  float cos_in;       // |cos| between the geometric normal and the arriving segment
  vec3 n_surface;     // shading normal as the surface has it (not turned to the arriving side)
  SurfacePoint point;
};

// The vertex at surface `s` of material `m`, reached along `dir_in`.
Vertex make_vertex_with(SurfaceHit s, SurfaceMaterial m, RayHit h, uint lod, vec3 dir_in) {
  Vertex v;
  float cos_hit = dot(s.geo_normal, -dir_in);
  bool front = cos_hit > 0.0;
  v.position = s.position;
  v.ng = front ? s.geo_normal : -s.geo_normal;
  v.ns = front ? s.shading_normal : -s.shading_normal;
  make_onb(v.ns, v.t, v.b);
  v.wo = to_local(-dir_in, v.t, v.b, v.ns);
  v.bsdf = m.bsdf;
  v.rough = rough_vertex(v.bsdf.alpha, max(v.bsdf.f0.r, max(v.bsdf.f0.g, v.bsdf.f0.b)));
  v.double_sided = m.double_sided;
  v.material_emission = m.light_emission;
  v.emission = (front || v.double_sided) ? m.emission : vec3(0.0);
  v.area = s.area;
  v.cos_in = abs(cos_hit);
  v.n_surface = s.shading_normal;
  v.point.instance = h.instance;
  v.point.geometry = h.geometry;
  v.point.triangle = h.triangle;
  v.point.bary = h.bary;
  v.point.lod = lod;
  return v;
}

// `spread`: camera_spread of the vertex's frame at a primary vertex, 0 past it (the scene bridge's
// footprint rule: the footprint is the target path's own, whichever frame and pixel it is built for).
// A fixed primary vertex takes its material from the primary stage instead (fixed_primary_vertex).
Vertex make_vertex(SurfaceHit s, RayHit h, uint lod, vec3 dir_in, float spread) {
  return make_vertex_with(s, material_at(s, primary_footprint(spread, s.position, dot(s.geo_normal, dir_in))), h, lod, dir_in);
}

// The primary vertex of a visibility-buffer entry (index `entry` in its frame), reached by the ray
// `dir_in` through its camera sample: its surface and its material as the primary stage recorded them.
Vertex fixed_primary_vertex(bool prev, GpuPrimaryHit e, uint entry, RayHit h, vec3 dir_in) {
  SurfaceHit s = primary_surface_hit(prev, e);
  return make_vertex_with(s, fixed_primary_material(prev, entry, s), h, e.lod, dir_in);
}

// The direction that a path's random numbers (`seed`) choose by BSDF sampling at its vertex
// x_j = v, as the candidate generator drew it and every replay draws it again, with f_s |cos| and
// the density; false where the lobe sample is unusable or leaves below the surface.
bool replay_bsdf_direction(Vertex v, uint seed, uint j, out vec3 dir, out vec3 fs, out float pdf) {
  uint base = dim_vertex(j) + DIM_BSDF;
  vec3 u = vec3(rng_dim(seed, base), rng_dim(seed, base + 1u), rng_dim(seed, base + 2u));
  vec3 wi;
  vec3 weight;
  dir = vec3(0.0, 0.0, 1.0);
  fs = vec3(0.0);
  if (!bsdf_sample(v.bsdf, v.wo, u, wi, weight, pdf)) return false;
  dir = to_world(wi, v.t, v.b, v.ns);
  fs = weight * pdf;
  return dot(dir, v.ng) > 0.0;
}

// The vertex a ray found in the current (prev = false) or the previous frame; `spread` as for make_vertex.
Vertex load_vertex(bool prev, RayHit h, vec3 dir_in, float spread) {
  return make_vertex(load_hit_in(prev, h), h, instance_in(prev, h.instance).lod, dir_in, spread);
}

// f(wo, d) |cos| at v; zero when d leaves below the geometric surface (reflection only).
vec3 scatter(Vertex v, vec3 d) {
  if (dot(d, v.ng) <= 0.0) return vec3(0.0);
  return bsdf_eval_cos(v.bsdf, v.wo, to_local(d, v.t, v.b, v.ns));
}

float scatter_pdf(Vertex v, vec3 d) {
  if (dot(d, v.ng) <= 0.0) return 0.0;
  return bsdf_pdf(v.bsdf, v.wo, to_local(d, v.t, v.b, v.ns));
}

// The surface frame of a vertex: an orthonormal basis around its shading normal that does not
// depend on the side a path arrives from, and turns with the object (the normal does). A direction
// kept in it (a reconnection vertex's outgoing direction, restir/reservoir.h) maps between frames
// by a rotation, whose solid-angle Jacobian is 1.
vec3 surface_to_local(Vertex v, vec3 d) {
  vec3 t;
  vec3 b;
  make_onb(v.n_surface, t, b);
  return vec3(dot(d, t), dot(d, b), dot(d, v.n_surface));
}

vec3 frame_to_world(vec3 n_surface, vec3 l) {
  vec3 t;
  vec3 b;
  make_onb(n_surface, t, b);
  return normalize(l.x * t + l.y * b + l.z * n_surface);
}

vec3 surface_to_world(Vertex v, vec3 l) { return frame_to_world(v.n_surface, l); }

vec3 spawn(Vertex v) { return offset_ray_origin(v.position, v.ng); }

// The surface at v as light sampling weighs lights for it (material/bsdf.h).
vec4 light_receiver(Vertex v) { return bsdf_light_receiver(v.ng, v.bsdf); }

// The light-sampling density at vertex v of the emitter point w that a path reached from it by BSDF
// sampling, `dist` away, in either frame (the scene bridge's, sanitized like every weight;
// light_pdf_environment is the bridge's).
float light_pdf_emitter(bool prev, Vertex v, Vertex w, float dist) {
  return gris_sanitize(emitter_light_pdf(prev, v.position, light_receiver(v), uvec3(w.point.instance, w.point.geometry, w.point.triangle), w.material_emission, w.area, w.double_sided, dist, w.cos_in));
}

// The MIS weight of the technique that produced the path's last vertex, power heuristic with the
// number of light candidates per vertex (Veach 1997 9.2.4); it is part of the target function, so
// NEE and BSDF sampling of the same path are two disjoint parts of the sample space.
float technique_weight(bool nee, float light_pdf, float bsdf_pdf_value) {
  float pl = float(restir_light_candidates()) * light_pdf;
  return nee ? mis_power(pl, bsdf_pdf_value) : mis_power(bsdf_pdf_value, pl);
}

// Reconnectability of path vertices: the rules of restir/reconnection.h.
bool rule_intermediate(Vertex before, Vertex v, float edge, float camera_distance) {
  return reconnectable(before.rough, v.rough, edge, camera_distance, v.cos_in);
}

bool rule_end(Vertex before, bool escaped, float edge, float camera_distance, float cos_end) {
  return reconnectable_end(before.rough, escaped, edge, camera_distance, cos_end);
}

#endif
