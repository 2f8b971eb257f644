// The lights of the scene bridge (include/scene_bridge.glsl includes this file at its end; a pass
// includes the bridge, never this file): next-event estimation's light sample and its density in
// either frame, the density of a light hit by another strategy, and the environment. The light
// table holds the emissive triangles and, in scenes that have them, the punctual lights
// (KHR_lights_punctual; compiled in by SPEC_PUNCTUAL, bound only then). One of two light samplers
// chooses among them (the session's light_sampler): an alias table by power, or, compiled in by
// SPEC_LIGHT_TREE, the frame's light tree by importance at the shading point (include/light_tree_data.h;
// directional lights by power beside it), so that a light's probability depends on where it is
// chosen from. The environment is chosen with probability env_select_prob: a constant
// colour (sampled uniformly over the sphere), or an equirectangular map (compiled in by SPEC_ENV_MAP,
// read by the device address of the frame constants; sampled by luminance x solid angle).
// Solid-angle densities throughout, except for a punctual light: a delta, whose sample's `pdf` is
// the probability of choosing it. The emitter and light records and the frame's light totals are
// read here only.
#ifndef STRATA_SCENE_LIGHTS_GLSL
#define STRATA_SCENE_LIGHTS_GLSL
#extension GL_EXT_buffer_reference : require
#extension GL_EXT_buffer_reference_uvec2 : require

#include "include/bindings.h"
#include "include/environment_data.h"
#include "include/frame_data.h"
#include "include/scene_data.h"
#include "restir/gris.h"
#include "sampling/emitter_pdf.h"
#include "sampling/warp.h"

layout(set = 0, binding = BINDING_EMITTERS, std430) readonly buffer Emitters { GpuEmitter b_emitters[]; };
layout(set = 0, binding = BINDING_ALIAS, std430) readonly buffer Alias { GpuAliasEntry b_alias[]; };

// Punctual lights: this frame's records, and the previous frame's (its render space), by the
// device addresses of the frame constants: no descriptor, so a scene without them binds nothing
// and, with SPEC_PUNCTUAL off, compiles none of their code.
layout(constant_id = SPEC_PUNCTUAL) const bool k_punctual = false;
layout(buffer_reference, std430, buffer_reference_align = 16) readonly buffer PunctualLights { GpuPunctualLight records[]; };
GpuPunctualLight punctual_in(bool prev, uint i) { return PunctualLights(prev ? u_frame.prev_lights : u_frame.lights).records[i]; }

#include "include/scene_light_tree.glsl"

struct LightSample {
  vec3 direction;     // unit, from the shading point
  float distance;     // to the sampled point; infinite for the environment
  vec3 radiance;      // emitted towards the shading point (0 if it sees the back face)
  float pdf;          // solid angle, including the selection probability
  // The sampled point as a surface point (what a ReSTIR path sample stores), unset for the environment.
  uint instance;
  uint geometry;
  uint triangle;
  vec2 bary;          // hit-convention barycentrics (weights of the triangle's vertices 1 and 2)
  float area;         // render-space triangle area
  float cos_light;    // |cos| at the emitter towards the shading point (1 for a punctual light)
  bool delta;         // a punctual light: BSDF sampling never finds it (its MIS weight is 1), `pdf` is a probability
  uint light;         // a punctual light's index (the scene's; its entry in the table is emitter_count + light)
};

// Solid-angle density of sampling a point on an emitter of `area` seen at `distance` under
// `cos_light`, given its selection probability (of a sampled emitter: its alias-table pmf; an
// emitter hit by another strategy uses sampling/emitter_pdf.h).
float emitter_pdf_solid_angle(float select_pmf, float area, float distance, float cos_light) {
  if (!(area > 0.0)) return 0.0;
  return area_to_solid_angle_pdf(select_pmf / area, distance * distance, cos_light);
}

// The environment map (scenes that have one, SPEC_ENV_MAP): its record and tables by device
// address (include/environment_data.h); the same map in both frames (a session constant).
layout(constant_id = SPEC_ENV_MAP) const bool k_env_map = false;
layout(buffer_reference, std430, buffer_reference_align = 16) readonly buffer EnvironmentMapRecord { GpuEnvironmentMap map; };
layout(buffer_reference, std430, buffer_reference_align = 16) readonly buffer EnvironmentTexels { vec4 texels[]; };
layout(buffer_reference, std430, buffer_reference_align = 4) readonly buffer EnvironmentCdf { float values[]; };

GpuEnvironmentMap env_map() { return EnvironmentMapRecord(u_frame.environment_map).map; }

// The map's texel that a unit direction falls in.
uvec2 env_map_texel(GpuEnvironmentMap m, vec3 dir, out float v) {
  vec2 uv = environment_map_uv(dir, m.rotation_cos, m.rotation_sin);
  v = uv.y;
  return environment_map_texel(uv, m.width, m.height);
}

// Probability that the map's sampler picks texel (i, j): its row's by the marginal CDF times its
// column's by the row's conditional CDF.
float env_map_texel_probability(GpuEnvironmentMap m, uint i, uint j) {
  EnvironmentCdf marginal = EnvironmentCdf(m.marginal);
  EnvironmentCdf conditional = EnvironmentCdf(m.conditional);
  uint row = j * (m.width + 1u);
  return (marginal.values[j + 1u] - marginal.values[j]) * (conditional.values[row + i + 1u] - conditional.values[row + i]);
}

// Solid-angle density with which the map's sampler (alone) picks a unit direction.
float env_map_pdf(vec3 dir) {
  GpuEnvironmentMap m = env_map();
  float v;
  uvec2 t = env_map_texel(m, dir, v);
  return environment_map_solid_angle_pdf(env_map_texel_probability(m, t.x, t.y), m.width, m.height, v);
}

// Index k of n intervals with cdf[k] <= x < cdf[k + 1], over the n + 1 entries from `base`
// (ascending, 0 to 1), never an empty interval: a row or texel of zero weight is never chosen.
uint env_map_find_interval(EnvironmentCdf cdf, uint base, uint n, float x) {
  uint lo = 0u, hi = n + 1u;  // the first entry above x lies in [lo, hi]
  while (lo < hi) {
    uint mid = (lo + hi) / 2u;
    if (cdf.values[base + mid] <= x) lo = mid + 1u;
    else hi = mid;
  }
  uint k = min(lo == 0u ? 0u : lo - 1u, n - 1u);
  while (k > 0u && !(cdf.values[base + k + 1u] > cdf.values[base + k])) --k;  // x at the top of an empty tail
  return k;
}

// A direction by the map's sampler from u in [0, 1)^2: a row by the marginal CDF, a column by the
// row's conditional CDF, then uniformly within the texel in UV.
vec3 env_map_sample(vec2 u) {
  GpuEnvironmentMap m = env_map();
  EnvironmentCdf marginal = EnvironmentCdf(m.marginal);
  EnvironmentCdf conditional = EnvironmentCdf(m.conditional);
  uint j = env_map_find_interval(marginal, 0u, m.height, u.y);
  uint row = j * (m.width + 1u);
  uint i = env_map_find_interval(conditional, row, m.width, u.x);
  float dv = (u.y - marginal.values[j]) / (marginal.values[j + 1u] - marginal.values[j]);
  float du = (u.x - conditional.values[row + i]) / (conditional.values[row + i + 1u] - conditional.values[row + i]);
  vec2 uv = vec2((float(i) + clamp(du, 0.0, 1.0)) / float(m.width), (float(j) + clamp(dv, 0.0, 1.0)) / float(m.height));
  return environment_map_direction(uv, m.rotation_cos, m.rotation_sin);
}

// The environment's radiance arriving along -dir: the constant, or the map's texel (nearest: the
// radiance is piecewise constant over the texels the sampler's density is constant over). The same
// in both frames.
vec3 environment_radiance(vec3 dir) {
  if (!k_env_map) return u_frame.environment.rgb;
  GpuEnvironmentMap m = env_map();
  float v;
  uvec2 t = env_map_texel(m, normalize(dir), v);
  return EnvironmentTexels(m.radiance).texels[t.y * m.width + t.x].rgb;
}

// Whether the environment emits at all (a camera ray that escapes sees emission).
bool environment_emits() { return k_env_map || luminance(u_frame.environment.rgb) > 0.0; }

// Whether next-event estimation samples the environment.
bool env_is_sampled() { return u_frame.environment.a > 0.0; }

// Solid-angle density with which the environment's own sampler picks a unit direction: the map's,
// or uniform over the sphere.
float environment_direction_pdf(vec3 dir) { return k_env_map ? env_map_pdf(normalize(dir)) : 1.0 / (4.0 * PI); }

// The current frame's light sampler's density of an escaped direction (0 unless NEE samples the environment).
float environment_pdf(vec3 dir) {
  if (!env_is_sampled()) return 0.0;
  return u_frame.env_select_prob * environment_direction_pdf(dir);
}

// The density with which either frame's light sampler picks a point on emitter triangle `tri`
// (instance, geometry, triangle) that another strategy hit from x (that frame's render space;
// `receiver` the surface there, as light sampling at x took it), `dist` away under cos_light: with
// the tree, that frame's tree's
// probability of the triangle's entry at x, per area, as a solid angle; else sampling/emitter_pdf.h
// with that frame's totals. `emission` is what the power weighs (SurfaceMaterial::light_emission).
float emitter_light_pdf(bool prev, vec3 x, vec4 receiver, uvec3 tri, vec3 emission, float area, bool double_sided, float dist,
                        float cos_light) {
  float env_select = prev ? u_frame.prev_env_select_prob : u_frame.env_select_prob;
  if (k_light_tree) {
    LightTreeRef t = light_tree_of(prev);
    float pmf = (1.0 - env_select) * light_tree_select(t, x, receiver, light_tree_entry(t, tri.x, tri.y, tri.z));
    return emitter_pdf_solid_angle(pmf, area, dist, cos_light);
  }
  float total = prev ? u_frame.prev_total_emitter_power : u_frame.total_emitter_power;
  return emitter_solid_angle_pdf(total, env_select, emission, area, double_sided, dist, cos_light);
}

// Either frame's light sampler's density of an escaped direction (the map is the same in both).
float light_pdf_environment(bool prev, vec3 dir) {
  if (!env_is_sampled()) return 0.0;
  return (prev ? u_frame.prev_env_select_prob : u_frame.env_select_prob) * environment_direction_pdf(dir);
}

// Whether a light density is the same in both frames: with the tree, no light changed between them
// (HISTORY_LIGHTS_CHANGED); else the emitter power totals of the two frames agree (to 1e-5: with
// the camera, render-space emitter areas change in their last bits, as GpuScene's light-selection
// test allows; the environment's share is a session constant).
bool light_totals_unchanged() {
  if (k_light_tree) return (u_frame.history_flags & HISTORY_LIGHTS_CHANGED) == 0u;
  float power = max(u_frame.total_emitter_power, u_frame.prev_total_emitter_power);
  return !(abs(u_frame.total_emitter_power - u_frame.prev_total_emitter_power) > 1e-5 * power);
}

LightSample light_sample_none() {
  LightSample ls;
  ls.direction = vec3(0.0, 0.0, 1.0);
  ls.distance = 0.0;
  ls.radiance = vec3(0.0);
  ls.pdf = 0.0;
  ls.instance = 0xFFFFFFFFu;
  ls.geometry = 0u;
  ls.triangle = 0u;
  ls.bary = vec2(0.0);
  ls.area = 0.0;
  ls.cos_light = 1.0;
  ls.delta = false;
  ls.light = 0u;
  return ls;
}

// Entries of the light table: the emissive triangles, then the punctual lights where compiled in.
uint light_table_size() { return k_punctual ? u_frame.emitter_count + u_frame.light_count : u_frame.emitter_count; }

// What punctual light `l` casts at x: the unit direction towards it, its distance (infinite for a
// directional light), and `radiance`, the quantity that multiplies f |cos| in the contribution of
// the light (a delta in direction): for a point or spot light I / d^2 times the spot falloff and
// the range window, for a directional light its irradiance. KHR_lights_punctual's reference:
//   spot falloff  a = clamp(cd scale + offset, 0, 1)^2, cd = cos of the angle from the spot's axis
//                 (scale, offset from the cones: render/punctual_lights.h), so 0 outside the outer
//                 cone, 1 inside the inner one and a smooth ramp between;
//   range window  clamp(1 - (d / range)^4, 0, 1) (the extension's recommended window).
// False where the light casts nothing at x.
bool punctual_arrival(GpuPunctualLight l, vec3 x, out vec3 dir, out float dist, out vec3 radiance) {
  uint type = uint(l.direction_type.w);
  dir = -l.direction_type.xyz;
  dist = 1.0 / 0.0;
  radiance = l.intensity_pmf.rgb;
  if (type == PUNCTUAL_DIRECTIONAL) return luminance(radiance) > 0.0;
  vec3 d = l.position_range.xyz - x;
  float dist2 = dot(d, d);
  if (!(dist2 > 0.0)) return false;
  dist = sqrt(dist2);
  dir = d / dist;
  float attenuation = 1.0 / dist2;
  float range = l.position_range.w;
  if (range > 0.0) {
    float q = dist2 / (range * range);
    attenuation *= clamp(1.0 - q * q, 0.0, 1.0);
  }
  if (type == PUNCTUAL_SPOT) {
    float a = clamp(dot(l.direction_type.xyz, -dir) * l.cone.x + l.cone.y, 0.0, 1.0);
    attenuation *= a * a;
  }
  radiance *= attenuation;
  return luminance(radiance) > 0.0 && !isinf(luminance(radiance));
}

// Punctual light `light` as seen from x in either frame (its record of that frame), as a light
// sample whose `pdf` is `pmf`, the probability with which that frame's sampler chose it.
bool punctual_light_with(bool prev, uint light, vec3 x, float pmf, out LightSample ls) {
  ls = light_sample_none();
  GpuPunctualLight l = punctual_in(prev, light);
  if (!punctual_arrival(l, x, ls.direction, ls.distance, ls.radiance)) return false;
  ls.delta = true;
  ls.light = light;
  ls.pdf = pmf;
  return ls.pdf > 0.0;
}

// The same, its probability that of the frame's sampler at x (`receiver`): its tree's (the light is entry
// `emitters + light` of that frame's table), or its power share.
bool punctual_light_at(bool prev, uint light, vec3 x, vec4 receiver, out LightSample ls) {
  float env_select = prev ? u_frame.prev_env_select_prob : u_frame.env_select_prob;
  float pmf;
  if (k_light_tree) {
    LightTreeRef t = light_tree_of(prev);
    pmf = (1.0 - env_select) * light_tree_select(t, x, receiver, t.h.entry_count - u_frame.light_count + light);
  } else {
    pmf = (1.0 - env_select) * punctual_in(prev, light).intensity_pmf.w;
  }
  return punctual_light_with(prev, light, x, pmf, ls);
}

const uint LIGHT_ENVIRONMENT = 0xFFFFFFFFu;

// The light that random numbers u choose at x in either frame: LIGHT_ENVIRONMENT, or an entry of the
// light table (an emitter below `emitters`, that frame's emitter count; a punctual light from there
// on). u.z picks (rescaled at each choice); u.xy is left for the point on it. With the tree,
// `pmf` is the probability of the choice in that frame; with the alias table (by power, the
// current frame's table for both frames) it is left to the caller. False when there is nothing
// to choose.
bool choose_light(bool prev, vec3 x, vec4 receiver, vec3 u, out uint index, out uint emitters, out float pmf) {
  index = LIGHT_ENVIRONMENT;
  emitters = u_frame.emitter_count;
  pmf = 0.0;
  if (k_light_tree) {
    float env_select = prev ? u_frame.prev_env_select_prob : u_frame.env_select_prob;
    LightTreeRef t = light_tree_of(prev);
    emitters = t.h.entry_count - (k_punctual ? u_frame.light_count : 0u);
    if (u.z < env_select || t.h.entry_count == 0u) {
      pmf = env_select;
      return env_select > 0.0;
    }
    if (!light_tree_sample(t, x, receiver, (u.z - env_select) / (1.0 - env_select), index, pmf)) return false;
    pmf *= 1.0 - env_select;
    return true;
  }
  uint count = light_table_size();
  if (u.z < u_frame.env_select_prob || count == 0u) return u_frame.env_select_prob > 0.0;
  float v = (u.z - u_frame.env_select_prob) / (1.0 - u_frame.env_select_prob);
  float scaled = v * float(count);
  uint column = min(uint(scaled), count - 1u);
  float coin = scaled - float(column);
  GpuAliasEntry entry = b_alias[column];
  index = coin < entry.threshold ? column : entry.alias;
  return true;
}

// The environment as light sample u chose it, in either frame: its radiance and density are those
// of the direction (the texel it falls in), as every other strategy evaluates them for MIS.
LightSample environment_light_sample(bool prev, vec3 u) {
  LightSample ls = light_sample_none();
  ls.direction = k_env_map ? env_map_sample(u.xy) : sample_uniform_sphere(u.xy);
  ls.distance = 1.0 / 0.0;
  ls.radiance = environment_radiance(ls.direction);
  ls.pdf = light_pdf_environment(prev, ls.direction);
  return ls;
}

// The current frame's light sample u seen from x, on the surface `receiver` describes (its
// geometric normal on the side the path arrives from and whether it is rough: bsdf_light_receiver;
// the tree's receiver factor), with its radiance and solid-angle density; false when it is
// unusable (a one-sided emitter seen from behind, a degenerate triangle).
bool sample_light(vec3 x, vec4 receiver, vec3 u, out LightSample ls) {
  ls = light_sample_none();
  uint index, emitters;
  float pmf;
  if (!choose_light(false, x, receiver, u, index, emitters, pmf)) return false;
  if (index == LIGHT_ENVIRONMENT) {
    ls = environment_light_sample(false, u);
    return ls.pdf > 0.0;
  }
  if (k_punctual && index >= emitters) {
    if (k_light_tree) return punctual_light_with(false, index - emitters, x, pmf, ls);
    return punctual_light_at(false, index - emitters, x, receiver, ls);
  }
  GpuEmitter e = b_emitters[index];

  vec2 b = sample_triangle_barycentrics(u.xy);
  vec3 p0 = e.p0_area.xyz;
  vec3 p1 = e.p1_pmf.xyz;
  vec3 p2 = e.p2_flags.xyz;
  vec3 y = (1.0 - b.x - b.y) * p0 + b.x * p1 + b.y * p2;
  vec3 d = y - x;
  float dist2 = dot(d, d);
  if (!(dist2 > 0.0)) return false;
  float dist = sqrt(dist2);
  ls.direction = d / dist;
  ls.distance = dist;
  vec3 c = cross(p1 - p0, p2 - p0);
  float clen = length(c);
  if (!(clen > 0.0)) return false;
  vec3 n_light = c / clen;
  float cos_light = -dot(n_light, ls.direction);
  bool double_sided = (floatBitsToUint(e.p2_flags.w) & MATERIAL_DOUBLE_SIDED) != 0u;
  if (cos_light <= 0.0 && !double_sided) return false;  // one-sided emitter seen from behind
  ls.instance = e.surface.x;
  ls.geometry = e.surface.y;
  ls.triangle = e.surface.z;
  ls.bary = e.surface.w != 0u ? b.yx : b;  // undo the re-winding of mirrored instances
  ls.radiance = emitter_radiance(false, e.emission.rgb, ls.instance, ls.geometry, ls.triangle, ls.bary);  // the texel there
  ls.area = e.p0_area.w;
  ls.cos_light = abs(cos_light);
  if (!k_light_tree) pmf = (1.0 - u_frame.env_select_prob) * e.p1_pmf.w;
  ls.pdf = emitter_pdf_solid_angle(pmf, e.p0_area.w, dist, cos_light);
  return ls.pdf > 0.0 && !isinf(ls.pdf);
}

// Light sample u from x in either frame (the NEE end of a replayed suffix, restir/suffix_replay.glsl).
// The current frame's is the initial pass's sample_light; in the previous frame that frame's
// sampler chooses (the tree: the previous frame's; the alias table: the same entry as this frame's,
// which HISTORY_LIGHTS_RESELECTED says is the previous frame's choice too), and the point with the
// same barycentrics is placed on its triangle as the previous frame's instance transform had it
// (resolve_surface); a punctual light is where the previous frame's record has it. The caller
// makes sure that the two frames' tables list the same lights (HISTORY_LIGHTS_RESELECTED).
bool sample_light_in(bool prev, vec3 x, vec4 receiver, vec3 u, out LightSample ls) {
  if (!prev) return sample_light(x, receiver, u, ls);
  ls = light_sample_none();
  uint index, emitters;
  float pmf;
  if (!choose_light(true, x, receiver, u, index, emitters, pmf)) return false;
  if (index == LIGHT_ENVIRONMENT) {
    ls = environment_light_sample(true, u);
    return ls.pdf > 0.0;
  }
  if (k_punctual && index >= emitters) {
    if (k_light_tree) return punctual_light_with(true, index - emitters, x, pmf, ls);
    return punctual_light_at(true, index - emitters, x, receiver, ls);
  }
  GpuEmitter e = b_emitters[index];
  vec2 b = sample_triangle_barycentrics(u.xy);
  SurfacePoint p;
  p.instance = e.surface.x;
  p.geometry = e.surface.y;
  p.triangle = e.surface.z;
  p.bary = e.surface.w != 0u ? b.yx : b;  // undo the re-winding of mirrored instances
  p.lod = instance_in(false, p.instance).lod;
  ResolvedSurface rs = resolve_surface_as(true, p, LOD_VERTEX_NONE);  // a light point: never mapped (its light is chosen anew)
  if (rs.reason != RESOLVE_OK) return false;
  vec3 d = rs.hit.position - x;
  float dist2 = dot(d, d);
  if (!(dist2 > 0.0)) return false;
  float dist = sqrt(dist2);
  ls.direction = d / dist;
  ls.distance = dist;
  float cos_light = -dot(rs.hit.geo_normal, ls.direction);
  bool double_sided = (floatBitsToUint(e.p2_flags.w) & MATERIAL_DOUBLE_SIDED) != 0u;
  if (cos_light <= 0.0 && !double_sided) return false;  // one-sided emitter seen from behind
  ls.radiance = emitter_radiance(true, e.emission.rgb, rs.ray.instance, rs.ray.geometry, rs.ray.triangle, rs.ray.bary);
  ls.instance = p.instance;
  ls.geometry = p.geometry;
  ls.triangle = p.triangle;
  ls.bary = p.bary;
  ls.area = rs.hit.area;
  ls.cos_light = abs(cos_light);
  ls.pdf = gris_sanitize(k_light_tree ? emitter_pdf_solid_angle(pmf, rs.hit.area, dist, ls.cos_light)
                                      : emitter_light_pdf(true, x, receiver, uvec3(p.instance, p.geometry, p.triangle), e.emission.rgb, rs.hit.area, double_sided, dist, ls.cos_light));
  return ls.pdf > 0.0 && !isinf(ls.pdf);
}

#endif
