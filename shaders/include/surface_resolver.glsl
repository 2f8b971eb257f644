// The surface resolver (docs/ARCHITECTURE.md, "Surface resolver"): the one place where a stored
// surface point (a primary hit, a reconnection vertex, a representative hit) becomes a hit in the
// current (prev = false) or previous frame. The point is stored in object space (instance,
// primitive, triangle, barycentrics at a LoD level), so it moves with its object's transform in
// that frame. When the instance shows another LoD level there, the LOD paper's vertex mapping tau
// finds its image at that level (lod_map, passes with history only); without it, or when tau has no
// image, the resolution fails. Part of the bridge: include/scene_bridge.glsl includes it after the
// instance records, hit loaders and ray queries it uses.
CONST_DEF uint RESOLVE_OK = 0u;
CONST_DEF uint RESOLVE_NONE = 1u;  // no surface stored, or an instance the scene does not have
CONST_DEF uint RESOLVE_LOD = 2u;   // the instance shows another LoD level in the target frame, and tau gave no image
// The kind of vertex a resolution is for (GpuLodHeader.vertices says which kinds tau maps).
CONST_DEF uint LOD_VERTEX_NONE = 0u;  // never mapped (a replayed light sample: its light was chosen anew)

struct ResolvedSurface {
  uint reason;       // RESOLVE_*
  SurfacePoint point;  // the point in the target frame's parametrisation: the stored one, or tau of it
  RayHit ray;        // the point as a ray query reports it (t = 0)
  SurfaceHit hit;    // loaded in the target frame (with instance 0 when the resolution failed)
  uint lod;          // the instance's level in the target frame
  float jacobian;    // |d tau / dx| in barycentric measure (lod_bary_jacobian; 1 while the triangle
                     // is kept): times hit.area over the stored triangle's area, LOD Eq. 6
  uint lod_mapping;  // LOD_MAPPING_NONE, LOD_MAPPED_* or LOD_FAIL_* (restir/lod_mapping.h)
  uint uv_rays;      // UV-space queries tau traced
};

#ifdef STRATA_HISTORY
// Off, the pipeline compiles without tau (lavapipe drops the branch before code generation): scenes
// without LoD groups, and lod_mapping off, pay nothing for it.
layout(constant_id = SPEC_LOD_MAPPING) const bool k_lod_mapping = false;
layout(set = 0, binding = BINDING_LOD_UV) uniform accelerationStructureEXT u_lod_uv;
layout(set = 0, binding = BINDING_LOD_TABLE, std430) readonly buffer LodTable {
  GpuLodHeader b_lod_header;
  GpuLodInstance b_lod[];
};

// A triangle of some level's mesh: object-space positions and UVs.
struct LodTriangle {
  vec3 p0, p1, p2;
  vec2 t0, t1, t2;
};

LodTriangle lod_triangle(uint primitive_base, uint geometry, uint triangle) {
  GpuPrimitive prim = b_primitives[primitive_base + geometry];
  uint base = prim.index_offset + 3u * triangle;
  GpuVertex v0 = b_vertices[prim.vertex_offset + b_indices[base]];
  GpuVertex v1 = b_vertices[prim.vertex_offset + b_indices[base + 1u]];
  GpuVertex v2 = b_vertices[prim.vertex_offset + b_indices[base + 2u]];
  LodTriangle t;
  t.p0 = v0.position_u.xyz;
  t.p1 = v1.position_u.xyz;
  t.p2 = v2.position_u.xyz;
  t.t0 = vec2(v0.position_u.w, v0.normal_v.w);
  t.t1 = vec2(v1.position_u.w, v1.normal_v.w);
  t.t2 = vec2(v2.position_u.w, v2.normal_v.w);
  return t;
}

vec3 lod_position(LodTriangle t, vec2 b) { return (1.0 - b.x - b.y) * t.p0 + b.x * t.p1 + b.y * t.p2; }
vec2 lod_uv(LodTriangle t, vec2 b) { return (1.0 - b.x - b.y) * t.t0 + b.x * t.t1 + b.y * t.t2; }

// X_i,v (LOD Eq. 4, 5): the distinct points of `level` of `instance` whose UV is v.
struct LodPoints {
  uint n;
  bool overflow;  // more than LOD_MAX_CANDIDATES
  uint geometry[LOD_MAX_CANDIDATES];
  uint triangle[LOD_MAX_CANDIDATES];
  vec2 bary[LOD_MAX_CANDIDATES];
  vec3 position[LOD_MAX_CANDIDATES];  // object space
};

// Every triangle of the level's UV layout that the query through (v, plane) along z meets: the UV
// TLAS holds the level's triangles at (u, v, 2 * plane) under instance mask 1 << level, and the
// query reports each as a candidate (no-opaque), never committing one (LOD 4.2: "find all candidate
// points"). The barycentrics of the UV triangle at v are those of the surface point.
LodPoints lod_points_at(uint instance, uint level, vec2 v, INOUT(uint) rays) {
  GpuLodInstance e = b_lod[instance];
  LodPoints c;
  c.n = 0u;
  c.overflow = false;
  rays++;
  rayQueryEXT rq;
  rayQueryInitializeEXT(rq, u_lod_uv, gl_RayFlagsNoOpaqueEXT, 1u << level, vec3(v, 2.0 * float(e.uv_plane) - 0.5), 0.0,
                        vec3(0.0, 0.0, 1.0), 1.0);
  while (rayQueryProceedEXT(rq)) {
    if (rayQueryGetIntersectionTypeEXT(rq, false) != gl_RayQueryCandidateIntersectionTriangleEXT) continue;
    if (uint(rayQueryGetIntersectionInstanceCustomIndexEXT(rq, false)) != instance) continue;
    uint g = uint(rayQueryGetIntersectionGeometryIndexEXT(rq, false));
    uint t = uint(rayQueryGetIntersectionPrimitiveIndexEXT(rq, false));
    vec2 b = rayQueryGetIntersectionBarycentricsEXT(rq, false);
    vec3 x = lod_position(lod_triangle(e.primitive_base[level], g, t), b);
    bool seen = false;  // the edge two triangles share is met twice
    for (uint i = 0u; i < c.n; ++i) seen = seen || same_lod_point(c.position[i], x);
    if (seen) continue;
    if (c.n == LOD_MAX_CANDIDATES) {
      c.overflow = true;
      continue;
    }
    c.geometry[c.n] = g;
    c.triangle[c.n] = t;
    c.bary[c.n] = b;
    c.position[c.n] = x;
    c.n++;
  }
  return c;
}

// tau (LOD 4.1-4.3): the image at `to_level` of the point p (on level p.lod of its instance), as
// `q`, with its barycentric Jacobian. Returns LOD_MAPPED_* or LOD_FAIL_*.
uint lod_map(SurfacePoint p, uint to_level, uint vertex_kind, OUT(SurfacePoint) q, OUT(float) jacobian, INOUT(uint) rays) {
  q = p;
  jacobian = 0.0;
  if (b_lod_header.mode != LOD_MODE_UV || (b_lod_header.vertices & vertex_kind) == 0u || p.instance >= b_lod_header.instances)
    return LOD_FAIL_OFF;
  GpuLodInstance e = b_lod[p.instance];
  if (p.lod >= e.levels || to_level >= e.levels) return LOD_FAIL_OFF;
  LodTriangle from = lod_triangle(e.primitive_base[p.lod], p.geometry, p.triangle);
  float uv2_from = uv_double_area(from.t0, from.t1, from.t2);
  if (!(uv2_from > 2.0 * LOD_MIN_UV_AREA)) return LOD_FAIL_DEGENERATE;
  vec2 v = lod_uv(from, p.bary);  // Phi_1(x)
  // X_2,v, then X_1,v (which holds p itself: found by position, the query's barycentrics differ from
  // p's by rounding). One call site: lavapipe inlines a traversal per call.
  LodPoints to_points;
  LodPoints from_points;
  for (uint side = 0u; side < 2u; ++side) {
    LodPoints found = lod_points_at(p.instance, side == 0u ? to_level : p.lod, v, rays);
    if (found.overflow) return LOD_FAIL_AMBIGUOUS;
    if (side == 0u && found.n == 0u) return LOD_FAIL_OUTSIDE;
    if (side == 0u) to_points = found;
    else from_points = found;
  }
  vec3 x = lod_position(from, p.bary);
  uint which = LOD_MAX_CANDIDATES;
  for (uint i = 0u; i < from_points.n; ++i)
    if (which == LOD_MAX_CANDIDATES && same_lod_point(from_points.position[i], x)) which = i;
  if (which == LOD_MAX_CANDIDATES) {
    if (from_points.n == LOD_MAX_CANDIDATES) return LOD_FAIL_AMBIGUOUS;
    which = from_points.n;
    from_points.position[which] = x;
    from_points.n++;
  }
  int chosen = 0;
  uint outcome = LOD_MAPPED_UNIQUE;
  if (from_points.n > 1u || to_points.n > 1u) {
    if (b_lod_header.matching == 0u) return LOD_FAIL_AMBIGUOUS;  // tau would not be a bijection
    chosen = lod_match(from_points.position, from_points.n, to_points.position, to_points.n, which);  // LOD Alg. 1
    if (chosen < 0) return LOD_FAIL_AMBIGUOUS;
    outcome = LOD_MAPPED_MATCHED;
  }
  uint c = uint(chosen);
  LodTriangle to = lod_triangle(e.primitive_base[to_level], to_points.geometry[c], to_points.triangle[c]);
  jacobian = lod_bary_jacobian(uv2_from, uv_double_area(to.t0, to.t1, to.t2));  // LOD Eq. 6 (barycentric part)
  if (!(jacobian > 0.0)) return LOD_FAIL_DEGENERATE;
  q.geometry = to_points.geometry[c];
  q.triangle = to_points.triangle[c];
  q.bary = to_points.bary[c];
  q.lod = to_level;
  return outcome;
}
#endif

ResolvedSurface resolve_surface_as(bool prev, SurfacePoint p, uint vertex_kind) {
  ResolvedSurface r;
  r.reason = RESOLVE_OK;
  r.jacobian = 1.0;
  r.lod_mapping = LOD_MAPPING_NONE;
  r.uv_rays = 0u;
  bool known = p.instance != SURFACE_NONE && p.instance < uint(b_instances.length());
  if (!known) r.reason = RESOLVE_NONE;
  GpuInstance inst = instance_in(prev, known ? p.instance : 0u);
  r.lod = inst.lod;
  SurfacePoint q = p;
  if (known && inst.lod != p.lod) {
#ifdef STRATA_HISTORY
    if (k_lod_mapping) r.lod_mapping = lod_map(p, inst.lod, vertex_kind, q, r.jacobian, r.uv_rays);
    else r.lod_mapping = LOD_FAIL_OFF;
#else
    r.lod_mapping = LOD_FAIL_OFF;  // one frame: every stored point is at the level it shows
#endif
    if (r.lod_mapping != LOD_MAPPED_UNIQUE && r.lod_mapping != LOD_MAPPED_MATCHED) r.reason = RESOLVE_LOD;
  }
  // A failed point loads triangle 0 of instance 0: its stored primitive may not exist at the level shown.
  bool ok = r.reason == RESOLVE_OK;
  r.point = ok ? q : p;
  r.ray.t = 0.0;
  r.ray.instance = ok ? q.instance : 0u;
  r.ray.geometry = ok ? q.geometry : 0u;
  r.ray.triangle = ok ? q.triangle : 0u;
  r.ray.bary = q.bary;
  r.hit = load_hit_with(ok ? inst : instance_in(prev, 0u), r.ray);
  if (!ok) r.jacobian = 0.0;
  return r;
}

// A primary hit (splat reprojection, backprojection, the disocclusion and domain tests).
ResolvedSurface resolve_surface(bool prev, SurfacePoint p) { return resolve_surface_as(prev, p, LOD_VERTEX_PRIMARY); }
