// The scene bridge's texture half (include/scene_bridge.glsl includes this file in its textured
// variant, STRATA_TEXTURES, after its bindings and hit records; a pass includes the bridge, never
// this file): the texCoords and UV density of a hit's triangle, the alpha test of ray-query
// candidates (SCENE_RAY_FLAGS, CONFIRM_ALPHA_TESTED) and normal mapping. Material lookups stay in
// the bridge's material_at.
#ifndef STRATA_SCENE_BRIDGE_TEXTURES_GLSL
#define STRATA_SCENE_BRIDGE_TEXTURES_GLSL
// The textured variant of a pass (scenes with textures or alpha-tested materials): texture lookups
// in material_at and load_hit, and with k_alpha_test the alpha test of every ray's candidates.
#include "include/textures.glsl"

// The texCoord sets of a primitive's triangle (xy set 0, zw set 1: TEXCOORD_1 where the scene has
// it), whose vertex records v0, v1, v2 are already read.
void vertex_texcoords(GpuVertex v0, GpuVertex v1, GpuVertex v2, GpuPrimitive prim, uint triangle, uint flags, out vec4 t0,
                      out vec4 t1, out vec4 t2) {
  t0 = vec4(v0.position_u.w, v0.normal_v.w, 0.0, 0.0);
  t1 = vec4(v1.position_u.w, v1.normal_v.w, 0.0, 0.0);
  t2 = vec4(v2.position_u.w, v2.normal_v.w, 0.0, 0.0);
  if ((flags & MATERIAL_VERTEX_EXTRAS) != 0u) {
    uint base = prim.index_offset + 3u * triangle;
    t0.zw = b_vertex_extras[prim.vertex_offset + b_indices[base]].uv1.xy;
    t1.zw = b_vertex_extras[prim.vertex_offset + b_indices[base + 1u]].uv1.xy;
    t2.zw = b_vertex_extras[prim.vertex_offset + b_indices[base + 2u]].uv1.xy;
  }
}

// The same, reading the vertex records.
void triangle_texcoords(GpuPrimitive prim, uint flags, uint triangle, out vec4 t0, out vec4 t1, out vec4 t2) {
  uint base = prim.index_offset + 3u * triangle;
  vertex_texcoords(b_vertices[prim.vertex_offset + b_indices[base]], b_vertices[prim.vertex_offset + b_indices[base + 1u]],
                   b_vertices[prim.vertex_offset + b_indices[base + 2u]], prim, triangle, flags, t0, t1, t2);
}

vec4 interpolate_texcoords(vec4 t0, vec4 t1, vec4 t2, vec2 bary) { return (1.0 - bary.x - bary.y) * t0 + bary.x * t1 + bary.y * t2; }

// UV units per render-space unit of each set over the triangle: sqrt(UV area / area), the
// triangle's Delta_0 of ray-cone texture LoD (Akenine-Moeller et al. 2019, Eq. 34) as a ratio.
vec2 texcoord_density(vec4 t0, vec4 t1, vec4 t2, float area) {
  vec4 a = t1 - t0;
  vec4 b = t2 - t0;
  vec2 uv_area = 0.5 * abs(vec2(a.x * b.y - a.y * b.x, a.z * b.w - a.w * b.z));
  return area > 0.0 ? sqrt(uv_area / area) : vec2(0.0);
}

layout(constant_id = SPEC_ALPHA_TEST) const bool k_alpha_test = false;

// Whether an alpha-tested candidate of a ray query is a surface (alpha_keeps at its texCoords).
bool candidate_kept(bool prev, uint instance, uint geometry, uint triangle, vec2 bary) {
  GpuPrimitive prim = b_primitives[instance_in(prev, instance).primitive_base + geometry];
  vec4 t0;
  vec4 t1;
  vec4 t2;
  triangle_texcoords(prim, b_material_textures[prim.material].flags, triangle, t0, t1, t2);
  return alpha_keeps(prim.material, interpolate_texcoords(t0, t1, t2, bary));
}

// Alpha-tested primitives are non-opaque BLAS geometry (gpu/accel.h, BlasTriangles::opaque): with
// k_alpha_test rays are not forced opaque, and every query confirms their candidates that pass the
// test (the rest of the scene stays opaque and never reaches the loop). Without it, and in the
// untextured variants, every ray is opaque and the loop is empty.
#define SCENE_RAY_FLAGS (k_alpha_test ? 0u : gl_RayFlagsOpaqueEXT)
#define CONFIRM_ALPHA_TESTED(rq, prev)                                                                    \
  if (k_alpha_test && rayQueryGetIntersectionTypeEXT(rq, false) == gl_RayQueryCandidateIntersectionTriangleEXT && \
      candidate_kept(prev, uint(rayQueryGetIntersectionInstanceCustomIndexEXT(rq, false)),                \
                     uint(rayQueryGetIntersectionGeometryIndexEXT(rq, false)),                            \
                     uint(rayQueryGetIntersectionPrimitiveIndexEXT(rq, false)),                           \
                     rayQueryGetIntersectionBarycentricsEXT(rq, false)))                                  \
    rayQueryConfirmIntersectionEXT(rq);

// The shading normal of a normal-mapped surface: the texel (finest level, as every lookup that is
// not a material's: the same normal for every path through the point) in the tangent frame. The
// tangent is the TANGENT attribute where the file gives it (bitangent = cross(n, t) w, glTF), else
// dP/du of the triangle in the normal texture's texCoord set, with the bitangent on the side of
// -dP/dv (glTF's green channel points towards decreasing v). Falls back to the interpolated normal
// where the frame degenerates.
vec3 normal_mapped(GpuInstance inst, GpuPrimitive prim, uint material, RayHit h, vec3 p0, vec3 p1, vec3 p2, vec4 t0,
                   vec4 t1, vec4 t2, SurfaceHit s) {
  vec3 n = s.shading_normal;
  vec3 t = vec3(0.0);
  float sign = 1.0;
  bool have = false;
  GpuTextureRef r = b_material_textures[material].slots[MATERIAL_TEXTURE_NORMAL];
  if ((b_material_textures[material].flags & MATERIAL_VERTEX_EXTRAS) != 0u) {
    uint base = prim.index_offset + 3u * h.triangle;
    vec4 a0 = b_vertex_extras[prim.vertex_offset + b_indices[base]].tangent;
    vec4 a1 = b_vertex_extras[prim.vertex_offset + b_indices[base + 1u]].tangent;
    vec4 a2 = b_vertex_extras[prim.vertex_offset + b_indices[base + 2u]].tangent;
    if (a0.w != 0.0) {
      vec3 t_obj = (1.0 - h.bary.x - h.bary.y) * a0.xyz + h.bary.x * a1.xyz + h.bary.y * a2.xyz;
      t = mat3(inst.object_to_render) * t_obj;
      // A mirroring transform turns cross(n, t) the other way round.
      sign = (a0.w < 0.0 ? -1.0 : 1.0) * ((inst.flags & INSTANCE_FLAG_MIRRORED) != 0u ? -1.0 : 1.0);
      have = true;
    }
  }
  if (!have) {
    vec2 d1 = r.tex_coord == 1u ? (t1 - t0).zw : (t1 - t0).xy;
    vec2 d2 = r.tex_coord == 1u ? (t2 - t0).zw : (t2 - t0).xy;
    float det = d1.x * d2.y - d1.y * d2.x;
    if (!(abs(det) > 1e-12)) return n;
    vec3 e1 = p1 - p0;
    vec3 e2 = p2 - p0;
    t = (e1 * d2.y - e2 * d1.y) / det;        // dP/du
    vec3 dv = (e2 * d1.x - e1 * d2.x) / det;  // dP/dv
    sign = dot(cross(n, t), -dv) < 0.0 ? -1.0 : 1.0;
  }
  t -= n * dot(n, t);
  float tl = length(t);
  if (!(tl > 0.0) || isinf(tl)) return n;
  t /= tl;
  vec3 b = cross(n, t) * sign;
  vec3 m = sample_texture_ref(r, s.uv, s.uv_density, 0.0).xyz * 2.0 - 1.0;
  m.xy *= b_material_textures[material].normal_scale;
  vec3 mapped = m.x * t + m.y * b + m.z * n;
  float ml = length(mapped);
  return ml > 0.0 && !isinf(ml) ? mapped / ml : n;
}

#endif
