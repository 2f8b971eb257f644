// The scene bridge (docs/ARCHITECTURE.md, "The scene bridge"): the one place that reads the scene's
// bindings and traces rays. Tracing in either frame, hit loading, the surface resolver, materials
// (material_at), and, in include/scene_lights.glsl which this file includes, light sampling, light
// densities and the environment; in the textured variant include/scene_bridge_textures.glsl holds
// the texCoords, the alpha test of ray candidates and normal mapping. The passes and the ReSTIR library (shaders/restir) call these
// functions; nothing else declares a scene binding or calls rayQuery*.
#ifndef STRATA_SCENE_BRIDGE_GLSL
#define STRATA_SCENE_BRIDGE_GLSL
#extension GL_EXT_ray_query : require

#include "include/bindings.h"
#include "include/frame_data.h"
#include "include/scene_data.h"
#include "material/bsdf.h"
#include "restir/lod_mapping.h"
#include "restir/primary_data.h"
#include "restir/reservoir.h"
#include "sampling/ray_offset.h"

layout(set = 0, binding = BINDING_TLAS) uniform accelerationStructureEXT u_tlas;
layout(set = 0, binding = BINDING_VERTICES, std430) readonly buffer Vertices { GpuVertex b_vertices[]; };
layout(set = 0, binding = BINDING_INDICES, std430) readonly buffer Indices { uint b_indices[]; };
layout(set = 0, binding = BINDING_PRIMITIVES, std430) readonly buffer Primitives { GpuPrimitive b_primitives[]; };
layout(set = 0, binding = BINDING_INSTANCES, std430) readonly buffer Instances { GpuInstance b_instances[]; };
layout(set = 0, binding = BINDING_MATERIALS, std430) readonly buffer Materials { GpuMaterial b_materials[]; };
// The frame's constants: camera, image, light totals, environment (include/frame_data.h). Declared
// here because the lights read them; the passes read them too, the ReSTIR library through its
// context (restir/context.glsl).
layout(set = 0, binding = BINDING_FRAME, std140) uniform Frame { GpuFrameConstants u_frame; };

GpuInstance instance_in(bool prev, uint i);

// What a ray query reports: enough to reload the hit later (a path sample stores exactly this).
struct RayHit {
  float t;
  uint instance;
  uint geometry;    // primitive of the instance's mesh
  uint triangle;
  vec2 bary;        // barycentrics of vertices 1 and 2
};

struct SurfaceHit {
  vec3 position;        // render space
  vec3 geo_normal;      // unit, front face (counter-clockwise winding in world)
  vec3 shading_normal;  // unit, interpolated, on the geometric normal's side
  float area;           // render-space triangle area
  uint material;
#ifdef STRATA_TEXTURES
  vec4 uv;              // texCoord sets at the hit: xy set 0, zw set 1
  vec2 uv_density;      // UV units per render-space unit over the triangle, per set (texcoord_density)
  uint triangle_index;  // the triangle's first index / 3 (per-triangle tables: b_light_emission)
#endif
};

#ifdef STRATA_TEXTURES
#include "include/scene_bridge_textures.glsl"
#else
#define SCENE_RAY_FLAGS gl_RayFlagsOpaqueEXT
#define CONFIRM_ALPHA_TESTED(rq, prev)
#endif

// The committed triangle hit of a finished query (false, and an empty hit, when it found none).
bool committed_hit(rayQueryEXT rq, out RayHit hit) {
  hit.t = 0.0;
  hit.instance = 0u;
  hit.geometry = 0u;
  hit.triangle = 0u;
  hit.bary = vec2(0.0);
  if (rayQueryGetIntersectionTypeEXT(rq, true) != gl_RayQueryCommittedIntersectionTriangleEXT) return false;
  hit.t = rayQueryGetIntersectionTEXT(rq, true);
  hit.instance = uint(rayQueryGetIntersectionInstanceCustomIndexEXT(rq, true));
  hit.geometry = uint(rayQueryGetIntersectionGeometryIndexEXT(rq, true));
  hit.triangle = uint(rayQueryGetIntersectionPrimitiveIndexEXT(rq, true));
  hit.bary = rayQueryGetIntersectionBarycentricsEXT(rq, true);
  return true;
}

bool trace_closest(vec3 origin, vec3 dir, float t_max, out RayHit hit) {
  rayQueryEXT rq;
  rayQueryInitializeEXT(rq, u_tlas, SCENE_RAY_FLAGS, 0xFF, origin, 0.0, dir, t_max);
  while (rayQueryProceedEXT(rq)) {
    CONFIRM_ALPHA_TESTED(rq, false)
  }
  return committed_hit(rq, hit);
}

// True when nothing blocks the segment origin -> origin + dir * t_max.
bool trace_visible(vec3 origin, vec3 dir, float t_max) {
  rayQueryEXT rq;
  rayQueryInitializeEXT(rq, u_tlas, SCENE_RAY_FLAGS | gl_RayFlagsTerminateOnFirstHitEXT, 0xFF,
                        origin, 0.0, dir, t_max);
  while (rayQueryProceedEXT(rq)) {
    CONFIRM_ALPHA_TESTED(rq, false)
  }
  return rayQueryGetIntersectionTypeEXT(rq, true) == gl_RayQueryCommittedIntersectionNoneEXT;
}


SurfaceHit load_hit_with(GpuInstance inst, RayHit h) {
  GpuPrimitive prim = b_primitives[inst.primitive_base + h.geometry];
  uint base = prim.index_offset + 3u * h.triangle;
  GpuVertex v0 = b_vertices[prim.vertex_offset + b_indices[base]];
  GpuVertex v1 = b_vertices[prim.vertex_offset + b_indices[base + 1u]];
  GpuVertex v2 = b_vertices[prim.vertex_offset + b_indices[base + 2u]];
  vec3 p0 = (inst.object_to_render * vec4(v0.position_u.xyz, 1.0)).xyz;
  vec3 p1 = (inst.object_to_render * vec4(v1.position_u.xyz, 1.0)).xyz;
  vec3 p2 = (inst.object_to_render * vec4(v2.position_u.xyz, 1.0)).xyz;
  float b0 = 1.0 - h.bary.x - h.bary.y;

  SurfaceHit s;
  // Interpolating the vertices is more precise than origin + t * dir (Waechter & Binder).
  s.position = b0 * p0 + h.bary.x * p1 + h.bary.y * p2;
  vec3 c = cross(p1 - p0, p2 - p0);
  float len = length(c);
  s.area = 0.5 * len;
  s.geo_normal = len > 0.0 ? c / len : vec3(0.0, 0.0, 1.0);
  if ((inst.flags & INSTANCE_FLAG_MIRRORED) != 0u) s.geo_normal = -s.geo_normal;
  vec3 n_obj = b0 * v0.normal_v.xyz + h.bary.x * v1.normal_v.xyz + h.bary.y * v2.normal_v.xyz;
  vec3 n = (inst.normal_to_render * vec4(n_obj, 0.0)).xyz;
  float nl = length(n);
  s.shading_normal = nl > 0.0 && !isnan(nl) ? n / nl : s.geo_normal;
#ifdef STRATA_TEXTURES
  s.uv = vec4(0.0);
  s.uv_density = vec2(0.0);
  s.triangle_index = prim.index_offset / 3u + h.triangle;
  uint textures = b_material_textures[prim.material].textures;
  if (textures != 0u) {  // an untextured material in a textured scene reads no texCoords
    vec4 t0;
    vec4 t1;
    vec4 t2;
    vertex_texcoords(v0, v1, v2, prim, h.triangle, b_material_textures[prim.material].flags, t0, t1, t2);
    s.uv = interpolate_texcoords(t0, t1, t2, h.bary);
    s.uv_density = texcoord_density(t0, t1, t2, s.area);
    if ((textures & (1u << MATERIAL_TEXTURE_NORMAL)) != 0u) s.shading_normal = normal_mapped(inst, prim, prim.material, h, p0, p1, p2, t0, t1, t2, s);
  }
#endif
  if (dot(s.shading_normal, s.geo_normal) < 0.0) s.shading_normal = -s.shading_normal;
  s.material = prim.material;
  return s;
}

SurfaceHit load_hit(RayHit h) { return load_hit_with(b_instances[h.instance], h); }

// The material of a surface, read once here: every BSDF evaluation, sample and density
// (material/bsdf.h: bsdf_eval_cos, bsdf_sample, bsdf_pdf on `bsdf`) and every emission the passes
// and the ReSTIR library compute reads this record, never the material buffer. A texture lookup
// at the hit belongs in material_at.
struct SurfaceMaterial {
  BsdfParams bsdf;
  float metallic;
  vec3 emission;      // radiance leaving the front face (and the back face when double_sided)
  // The emission light sampling selects the triangle by, in the densities of light sampling
  // (emitter_light_pdf): `emission` itself, but with an emissive texture the triangle's integrated
  // texture (render/scene_textures.h), which the emitter table was built with.
  vec3 light_emission;
  bool double_sided;
};

SurfaceMaterial material_of(uint material) {
  GpuMaterial m = b_materials[material];
  SurfaceMaterial s;
  s.bsdf = make_bsdf(m.base_color_metallic.rgb, m.base_color_metallic.a, m.emission_roughness.a, m.specular);
  s.metallic = m.base_color_metallic.a;
  s.emission = m.emission_roughness.rgb;
  s.light_emission = s.emission;
  s.double_sided = (m.flags & MATERIAL_DOUBLE_SIDED) != 0u;
  return s;
}

// The footprint rule of texture lookups (docs/ARCHITECTURE.md, "The scene bridge"): a ray cone
// (Akenine-Moeller et al. 2019) at the primary vertex, from the camera of the frame the vertex is in
// (the render-space origin) with the spread of one pixel, `spread` = camera_spread(prev): the
// footprint is spread x distance / |cos| at the vertex, in render-space units. Past the primary
// vertex the footprint is 0: the finest level, bilinear. The footprint is part of each pixel's
// integrand: a path's value at pixel i is defined with the footprint its own primary vertex has in
// pixel i's frame. So every shift evaluates the TARGET pixel's integrand: the shifted path's texels
// at the shifted path's footprint (its primary vertex in the target frame, which make_vertex of
// restir/path_vertex.glsl sees), never the base path's; the reconnection vertex and every vertex
// after it read the finest level in every frame and every shift.
float camera_spread(bool prev) {
  if (prev) return 2.0 * length(u_frame.prev_camera.up.xyz) / float(max(u_frame.prev_height, 1u));
  return 2.0 * length(u_frame.camera.up.xyz) / float(max(u_frame.height, 1u));
}

// The footprint width at a primary vertex at `position` (render space: the camera at the origin)
// seen under `cos_in`, for camera spread `spread` (0: the finest level).
float primary_footprint(float spread, vec3 position, float cos_in) {
  return spread > 0.0 ? spread * length(position) / max(abs(cos_in), 1e-2) : 0.0;
}

#ifdef STRATA_TEXTURES
// A textured material's factors at a point: what its textures give there, times the material's
// factors (the layout of GpuMaterial's first two records: base colour and metallic, emission and
// roughness).
struct MaterialFactors {
  vec4 base_color_metallic;
  vec4 emission_roughness;
};

// The material a hit's factors make: its BSDF, emission and the emission light sampling selects
// its triangle by (with an emissive texture the triangle's integrated texture).
SurfaceMaterial material_with(uint material, uint triangle_index, MaterialFactors f) {
  GpuMaterial m = b_materials[material];
  SurfaceMaterial r;
  r.bsdf = make_bsdf(f.base_color_metallic.rgb, f.base_color_metallic.a, f.emission_roughness.a, m.specular);
  r.metallic = f.base_color_metallic.a;
  r.emission = f.emission_roughness.rgb;
  r.light_emission = m.emission_roughness.rgb;
  if ((b_material_textures[material].textures & (1u << MATERIAL_TEXTURE_EMISSIVE)) != 0u) r.light_emission = b_light_emission[triangle_index].rgb;
  r.double_sided = (m.flags & MATERIAL_DOUBLE_SIDED) != 0u;
  return r;
}

// The factors of the material at a surface hit, its textures read with a footprint `footprint`
// wide in render space (the footprint rule above).
MaterialFactors material_factors(SurfaceHit s, float footprint) {
  GpuMaterial m = b_materials[s.material];
  vec3 base = m.base_color_metallic.rgb;
  float metallic = m.base_color_metallic.a;
  float roughness = m.emission_roughness.a;
  vec3 emission = m.emission_roughness.rgb;
  // The material's shading textures (base colour, metallic-roughness, emissive) in one loop over
  // those it has, each texture reference read in place from the buffer by its slot: each call site
  // of material_at then holds one lookup and one load of a reference, whose code lavapipe compiles
  // at every site (textures.glsl).
  uint textures = b_material_textures[s.material].textures;
  for (uint left = textures & MATERIAL_SHADING_TEXTURES; left != 0u; left &= left - 1u) {
    uint k = uint(findLSB(left));
    vec4 c = sample_texture_ref(b_material_textures[s.material].slots[k], s.uv, s.uv_density, footprint);
    if (k == MATERIAL_TEXTURE_BASE_COLOR) base *= c.rgb;
    if (k == MATERIAL_TEXTURE_METALLIC_ROUGHNESS) {
      roughness *= c.g;
      metallic *= c.b;
    }
    if (k == MATERIAL_TEXTURE_EMISSIVE) emission *= c.rgb;
  }
  MaterialFactors f;
  f.base_color_metallic = vec4(base, metallic);
  f.emission_roughness = vec4(emission, roughness);
  return f;
}
#endif

// The material at a surface hit (a loaded hit; a visibility-buffer entry's is the primary stage's
// record: fixed_primary_material, restir/context.glsl), its textures read with a footprint
// `footprint` wide in render space (the footprint rule above).
SurfaceMaterial material_at(SurfaceHit s, float footprint) {
#ifdef STRATA_TEXTURES
  return material_with(s.material, s.triangle_index, material_factors(s, footprint));
#else
  return material_of(s.material);
#endif
}

// The radiance a point of an emitter triangle emits towards a light sample's shading point (the
// scene bridge's lights, include/scene_lights.glsl): the emitter table's emission, or with an
// emissive texture the material's emission factor times the texel there at the finest level, as
// material_at gives it at every vertex past the primary one (the footprint rule), so that a light
// sample and a hit of the same point see the same radiance.
vec3 emitter_radiance(bool prev, vec3 table_emission, uint instance, uint geometry, uint triangle, vec2 bary) {
#ifdef STRATA_TEXTURES
  GpuPrimitive prim = b_primitives[instance_in(prev, instance).primitive_base + geometry];
  if ((b_material_textures[prim.material].textures & (1u << MATERIAL_TEXTURE_EMISSIVE)) == 0u) return table_emission;
  vec4 t0;
  vec4 t1;
  vec4 t2;
  triangle_texcoords(prim, b_material_textures[prim.material].flags, triangle, t0, t1, t2);
  vec4 texel = sample_texture_ref(b_material_textures[prim.material].slots[MATERIAL_TEXTURE_EMISSIVE], interpolate_texcoords(t0, t1, t2, bary), vec2(0.0), 0.0);
  return b_materials[prim.material].emission_roughness.rgb * texel.rgb;
#else
  return table_emission;
#endif
}

// Whether a material emits light (the emissive material kind).
bool material_emits(SurfaceMaterial m) { return any(greaterThan(m.emission, vec3(0.0))); }

// The same queries in either frame: `prev` selects the previous frame's TLAS and instance records
// (bound only in passes compiled with STRATA_HISTORY; elsewhere there is one frame).
#ifdef STRATA_HISTORY
layout(set = 0, binding = BINDING_TLAS_PREV) uniform accelerationStructureEXT u_tlas_prev;
layout(set = 0, binding = BINDING_INSTANCES_PREV, std430) readonly buffer InstancesPrev { GpuInstance b_instances_prev[]; };
layout(set = 0, binding = BINDING_SWEPT_BOXES, std430) readonly buffer SweptBoxes { GpuSweptBoxes b_swept; };

// Whether the ray from `origin` along `dir` (render space of the previous frame when `prev`) may
// meet an instance that changed between the two frames: it enters one of their swept boxes
// (GpuSweptBoxes), or they are too many to list. A ray that does not meets the same surfaces in
// both frames. Slab test; a NaN from a zero direction component counts as meeting the box.
bool ray_meets_change(bool prev, vec3 origin, vec3 dir) {
  if (b_swept.count > SWEPT_BOXES_MAX) return true;
  vec3 o = prev ? origin + b_swept.prev_to_current.xyz : origin;
  vec3 inv = 1.0 / dir;
  for (uint i = 0u; i < b_swept.count; ++i) {
    vec3 t0 = (b_swept.lo[i].xyz - o) * inv;
    vec3 t1 = (b_swept.hi[i].xyz - o) * inv;
    vec3 near = min(t0, t1);
    vec3 far = max(t0, t1);
    float enter = max(max(near.x, near.y), max(near.z, 0.0));
    float leave = min(min(far.x, far.y), far.z);
    if (!(enter > leave)) return true;
  }
  return false;
}

GpuInstance instance_in(bool prev, uint i) {
  // (Not a ?: between the two blocks: glslang then stores one block's struct type into the other's.)
  if (prev) return b_instances_prev[i];
  return b_instances[i];
}

bool trace_closest_in(bool prev, vec3 origin, vec3 dir, float t_max, out RayHit hit) {
  if (!prev) return trace_closest(origin, dir, t_max, hit);
  rayQueryEXT rq;
  rayQueryInitializeEXT(rq, u_tlas_prev, SCENE_RAY_FLAGS, 0xFF, origin, 0.0, dir, t_max);
  while (rayQueryProceedEXT(rq)) {
    CONFIRM_ALPHA_TESTED(rq, true)
  }
  return committed_hit(rq, hit);
}

#else
GpuInstance instance_in(bool prev, uint i) { return b_instances[i]; }
bool trace_closest_in(bool prev, vec3 origin, vec3 dir, float t_max, out RayHit hit) {
  return trace_closest(origin, dir, t_max, hit);
}
#endif

// Either kind of query in either frame through one traversal: the closest hit, or with `any_hit`
// whether anything blocks the segment (then `hit` is some hit on it). A loop that needs both
// kinds traces at a single call site (lavapipe inlines the traversal of each rayQueryProceedEXT).
// The segment is [t_min, t_max] along dir (trace_span; the ray probe pass takes t_min from the host).
bool trace_span(bool prev, vec3 origin, float t_min, vec3 dir, float t_max, bool any_hit, out RayHit hit) {
  uint flags = SCENE_RAY_FLAGS | (any_hit ? gl_RayFlagsTerminateOnFirstHitEXT : 0u);
  rayQueryEXT rq;
#ifdef STRATA_HISTORY
  if (prev) rayQueryInitializeEXT(rq, u_tlas_prev, flags, 0xFF, origin, t_min, dir, t_max);
  else
#endif
    rayQueryInitializeEXT(rq, u_tlas, flags, 0xFF, origin, t_min, dir, t_max);
  while (rayQueryProceedEXT(rq)) {
    CONFIRM_ALPHA_TESTED(rq, prev)
  }
  return committed_hit(rq, hit);
}

bool trace_query_in(bool prev, vec3 origin, vec3 dir, float t_max, bool any_hit, out RayHit hit) {
  return trace_span(prev, origin, 0.0, dir, t_max, any_hit, hit);
}

SurfaceHit load_hit_in(bool prev, RayHit h) { return load_hit_with(instance_in(prev, h.instance), h); }

// What changed about instance i between the previous frame and this one (INSTANCE_CHANGED_*).
uint instance_changes(uint i) { return b_instances[i].flags & INSTANCE_CHANGED; }

#include "include/surface_resolver.glsl"

// The hit of a visibility-buffer entry as its ray query reported it; false when the ray found none.
bool primary_hit(GpuPrimaryHit p, out RayHit h) {
  h.t = p.t;
  h.instance = p.instance;
  h.geometry = p.geometry;
  h.triangle = p.triangle;
  h.bary = p.bary;
  return (p.flags & PRIMARY_HIT) != 0u;
}

// The surface of a visibility-buffer entry's hit in the entry's own frame, as load_hit gave it to
// the primary stage (restir/primary_data.h); meaningful only when the entry has PRIMARY_HIT.
// `prev`: the entry is the previous frame's. Its texCoords are not read: the material there is the
// primary stage's record of it (fixed_primary_material, restir/context.glsl).
SurfaceHit primary_surface_hit(bool prev, GpuPrimaryHit p) {
  SurfaceHit s;
  s.position = p.position_area.xyz;
  s.area = p.position_area.w;
  s.geo_normal = p.geo_normal_material.xyz;
  s.material = floatBitsToUint(p.geo_normal_material.w);
  s.shading_normal = p.shading_normal_kind.xyz;  // normal-mapped where the material has a normal texture
#ifdef STRATA_TEXTURES
  s.uv = vec4(0.0);
  s.uv_density = vec2(0.0);
  s.triangle_index = 0u;
  if ((p.flags & PRIMARY_HIT) != 0u)
    s.triangle_index = b_primitives[instance_in(prev, p.instance).primitive_base + p.geometry].index_offset / 3u + p.triangle;
#endif
  return s;
}

// The surface point of a visibility-buffer entry (restir/primary_data.h).
SurfacePoint primary_surface(GpuPrimaryHit h) {
  SurfacePoint p;
  p.instance = (h.flags & PRIMARY_HIT) != 0u ? h.instance : SURFACE_NONE;
  p.geometry = h.geometry;
  p.triangle = h.triangle;
  p.bary = h.bary;
  p.lod = h.lod;
  return p;
}

#include "include/scene_lights.glsl"

#endif
