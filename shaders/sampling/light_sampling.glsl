// Next-event estimation: emissive triangles chosen by power through an alias table, and the
// constant environment chosen with probability env_select_prob. Solid-angle densities throughout.
#ifndef STRATA_LIGHT_SAMPLING_GLSL
#define STRATA_LIGHT_SAMPLING_GLSL

#include "include/bindings.h"
#include "include/frame_data.h"
#include "include/scene_data.h"
#include "sampling/warp.h"

layout(set = 0, binding = BINDING_EMITTERS, std430) readonly buffer Emitters { GpuEmitter b_emitters[]; };
layout(set = 0, binding = BINDING_ALIAS, std430) readonly buffer Alias { GpuAliasEntry b_alias[]; };

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
  float cos_light;    // |cos| at the emitter towards the shading point
};

// Solid-angle density of sampling a point on an emitter of `area` seen at `distance` under
// `cos_light`, given its selection probability (of a sampled emitter: its alias-table pmf; an
// emitter hit by another strategy uses sampling/emitter_pdf.h).
float emitter_pdf_solid_angle(float select_pmf, float area, float distance, float cos_light) {
  if (!(area > 0.0)) return 0.0;
  return area_to_solid_angle_pdf(select_pmf / area, distance * distance, cos_light);
}

float environment_pdf(GpuFrameConstants f) { return f.env_select_prob * (1.0 / (4.0 * PI)); }

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
  return ls;
}

const uint LIGHT_ENVIRONMENT = 0xFFFFFFFFu;

// The light that random numbers u choose: LIGHT_ENVIRONMENT, or an emitter of the alias table
// (u.z, rescaled, picks the column and its coin; u.xy is left for the point on it). False when
// there is nothing to choose.
bool choose_light(vec3 u, GpuFrameConstants f, out uint index) {
  index = LIGHT_ENVIRONMENT;
  if (u.z < f.env_select_prob || f.emitter_count == 0u) return f.env_select_prob > 0.0;
  float v = (u.z - f.env_select_prob) / (1.0 - f.env_select_prob);
  float scaled = v * float(f.emitter_count);
  uint column = min(uint(scaled), f.emitter_count - 1u);
  float coin = scaled - float(column);
  GpuAliasEntry entry = b_alias[column];
  index = coin < entry.threshold ? column : entry.alias;
  return true;
}

// The environment as light sample u chose it.
LightSample environment_light_sample(vec3 u, GpuFrameConstants f) {
  LightSample ls = light_sample_none();
  ls.direction = sample_uniform_sphere(u.xy);
  ls.distance = 1.0 / 0.0;
  ls.radiance = f.environment.rgb;
  ls.pdf = environment_pdf(f);
  return ls;
}

bool sample_light(vec3 x, vec3 u, GpuFrameConstants f, out LightSample ls) {
  ls = light_sample_none();
  uint index;
  if (!choose_light(u, f, index)) return false;
  if (index == LIGHT_ENVIRONMENT) {
    ls = environment_light_sample(u, f);
    return true;
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
  ls.radiance = e.emission.rgb;
  ls.instance = e.surface.x;
  ls.geometry = e.surface.y;
  ls.triangle = e.surface.z;
  ls.bary = e.surface.w != 0u ? b.yx : b;  // undo the re-winding of mirrored instances
  ls.area = e.p0_area.w;
  ls.cos_light = abs(cos_light);
  float pmf = (1.0 - f.env_select_prob) * e.p1_pmf.w;
  ls.pdf = emitter_pdf_solid_angle(pmf, e.p0_area.w, dist, cos_light);
  return ls.pdf > 0.0 && !isinf(ls.pdf);
}

#endif
