// The material model: glTF metallic-roughness as a Lambert lobe plus a GGX microfacet lobe.
//   f = diffuse / pi + D G2 F / (4 cos_o cos_i)
// with F = F0 + (F90 - F0)(1 - wo.h)^5 (Schlick), F0 = mix(0.04 specular, base, metallic) and
// F90 = mix(specular, 1, metallic): KHR_materials_specular scales the whole dielectric Fresnel term
// by its factor, so a factor of 0 leaves no specular lobe at any angle; diffuse = base (1 -
// metallic)(1 - 0.04 specular). D: GGX (Trowbridge-Reitz), G2: height-correlated Smith (Heitz 2014).
// Sampling: one lobe chosen by its Fresnel-weighted albedo; GGX by visible normals (Heitz 2018).
// Everything is in the local shading frame (normal = +z); callers orient the frame towards wo.
#ifndef STRATA_BSDF_H
#define STRATA_BSDF_H
#include "include/lang.h"
#include "sampling/warp.h"

STRATA_NAMESPACE_BEGIN

CONST_DEF float GGX_ALPHA_MIN = 1e-3f;  // below this the lobe is treated as this rough (stable D)

struct BsdfParams {
  vec3 diffuse;   // Lambert albedo
  vec3 f0;        // specular reflectance at normal incidence
  float f90;      // specular reflectance at grazing incidence
  float alpha;    // GGX alpha = roughness^2, clamped to GGX_ALPHA_MIN
};

INLINE BsdfParams make_bsdf(vec3 base_color, float metallic, float roughness, float specular) {
  BsdfParams p;
  float dielectric_f0 = 0.04f * specular;
  p.f0 = mix(vec3(dielectric_f0), base_color, metallic);
  p.f90 = mix(specular, 1.0f, metallic);
  p.diffuse = base_color * (1.0f - metallic) * (1.0f - dielectric_f0);
  p.alpha = max(roughness * roughness, GGX_ALPHA_MIN);
  return p;
}

INLINE float luminance(vec3 c) { return dot(c, vec3(0.2126f, 0.7152f, 0.0722f)); }

INLINE vec3 fresnel_schlick(vec3 f0, float f90, float cos_theta) {
  float m = clamp(1.0f - cos_theta, 0.0f, 1.0f);
  float m2 = m * m;
  return f0 + (vec3(f90) - f0) * (m2 * m2 * m);
}

INLINE float ggx_d(float alpha, float cos_h) {
  float a2 = alpha * alpha;
  float d = cos_h * cos_h * (a2 - 1.0f) + 1.0f;
  return a2 / (PI * d * d);
}

// Smith Lambda for GGX; cos_theta > 0.
INLINE float ggx_lambda(float alpha, float cos_theta) {
  float c2 = cos_theta * cos_theta;
  float a2_tan2 = alpha * alpha * max(0.0f, 1.0f - c2) / max(c2, 1e-12f);
  return 0.5f * (-1.0f + sqrt(1.0f + a2_tan2));
}

// Probability of sampling the GGX lobe; the diffuse lobe gets the rest.
INLINE float bsdf_specular_probability(BsdfParams p, float cos_o) {
  float ws = luminance(fresnel_schlick(p.f0, p.f90, cos_o));
  float wd = luminance(p.diffuse);
  if (!(ws + wd > 0.0f)) return 0.0f;
  return ws / (ws + wd);
}

// The surface at a shading point as the light tree weighs lights for it (sampling/light_tree.h,
// light_node_receiver): its geometric normal `ng` on the side the path arrives from, and 1 where
// its integrand falls with the cosine at the receiver towards the surface's plane, as a rough
// surface's does (GGX alpha at least BSDF_COSINE_RECEIVER_ALPHA, roughness 0.55), 0 for a glossy
// one, whose f cos theta_i stays large there.
CONST_DEF float BSDF_COSINE_RECEIVER_ALPHA = 0.3f;
INLINE vec4 bsdf_light_receiver(vec3 ng, BsdfParams p) {
  return vec4(ng, p.alpha >= BSDF_COSINE_RECEIVER_ALPHA ? 1.0f : 0.0f);
}

// f(wo, wi) * cos(theta_i); zero when either direction is below the surface.
INLINE vec3 bsdf_eval_cos(BsdfParams p, vec3 wo, vec3 wi) {
  if (wo.z <= 0.0f || wi.z <= 0.0f) return vec3(0.0f);
  vec3 result = p.diffuse * (INV_PI * wi.z);
  vec3 h = normalize(wo + wi);
  float d = ggx_d(p.alpha, h.z);
  float g2 = 1.0f / (1.0f + ggx_lambda(p.alpha, wo.z) + ggx_lambda(p.alpha, wi.z));
  vec3 f = fresnel_schlick(p.f0, p.f90, max(dot(wo, h), 0.0f));
  result += f * (d * g2 / (4.0f * wo.z));
  return result;
}

// Solid-angle density of bsdf_sample producing wi.
INLINE float bsdf_pdf(BsdfParams p, vec3 wo, vec3 wi) {
  if (wo.z <= 0.0f || wi.z <= 0.0f) return 0.0f;
  float ps = bsdf_specular_probability(p, wo.z);
  vec3 h = normalize(wo + wi);
  // Visible-normal density D_wo(h) = G1(wo) max(0, wo.h) D(h) / cos_o, times the reflection
  // Jacobian 1 / (4 wo.h): the wo.h factors cancel (Heitz 2018, Eq. 17).
  float g1 = 1.0f / (1.0f + ggx_lambda(p.alpha, wo.z));
  float pdf_spec = dot(wo, h) > 0.0f ? g1 * ggx_d(p.alpha, h.z) / (4.0f * wo.z) : 0.0f;
  float pdf_diff = wi.z * INV_PI;
  return ps * pdf_spec + (1.0f - ps) * pdf_diff;
}

// Visible GGX normal for view direction wo (Heitz 2018, "Sampling the GGX Distribution of Visible Normals").
INLINE vec3 ggx_sample_visible_normal(float alpha, vec3 wo, vec2 u) {
  vec3 vh = normalize(vec3(alpha * wo.x, alpha * wo.y, wo.z));
  float len2 = vh.x * vh.x + vh.y * vh.y;
  vec3 t1 = len2 > 0.0f ? vec3(-vh.y, vh.x, 0.0f) * inversesqrt(len2) : vec3(1.0f, 0.0f, 0.0f);
  vec3 t2 = cross(vh, t1);
  float r = sqrt(u.x);
  float phi = 2.0f * PI * u.y;
  float p1 = r * cos(phi);
  float p2 = r * sin(phi);
  float s = 0.5f * (1.0f + vh.z);
  p2 = (1.0f - s) * sqrt(max(0.0f, 1.0f - p1 * p1)) + s * p2;
  vec3 nh = p1 * t1 + p2 * t2 + sqrt(max(0.0f, 1.0f - p1 * p1 - p2 * p2)) * vh;
  return normalize(vec3(alpha * nh.x, alpha * nh.y, max(1e-6f, nh.z)));
}

// Samples wi; returns false when the sample is unusable. weight = f cos / pdf.
INLINE bool bsdf_sample(BsdfParams p, vec3 wo, vec3 u, OUT(vec3) wi, OUT(vec3) weight, OUT(float) pdf) {
  wi = vec3(0.0f);
  weight = vec3(0.0f);
  pdf = 0.0f;
  if (wo.z <= 0.0f) return false;
  float ps = bsdf_specular_probability(p, wo.z);
  if (u.z < ps) {
    vec3 h = ggx_sample_visible_normal(p.alpha, wo, vec2(u.x, u.y));
    wi = reflect(-wo, h);
  } else {
    wi = sample_cosine_hemisphere(vec2(u.x, u.y));
  }
  if (wi.z <= 0.0f) return false;
  pdf = bsdf_pdf(p, wo, wi);
  if (!(pdf > 0.0f) || isinf(pdf)) return false;
  weight = bsdf_eval_cos(p, wo, wi) / pdf;
  return true;
}

STRATA_NAMESPACE_END
#endif
