// The LoD vertex mapping tau of the LOD paper (Wang et al. 2026, seed 001), its math written once for
// the device (shaders/include/scene_bridge.glsl, resolve_surface) and the host's tests.
//   tau(x) = Phi_2^-1(Phi_1(x))                                         (LOD 4.1)
// A stored surface point x on level l_1 of an instance has UV coordinates v = Phi_1(x); its images
// at level l_2 are the points of that level with the same UV (X_2,v, LOD Eq. 5), found by a ray query
// in the instance's UV plane (render/lod_uv_space.h). Where the UV map is not one-to-one, the points
// of level l_1 with the same UV (X_1,v, LOD Eq. 4) are matched to those of level l_2 greedily by
// distance (LOD Alg. 1), in object space (LOD footnote 2: invariant under the instance's motion).
#ifndef STRATA_RESTIR_LOD_MAPPING_H
#define STRATA_RESTIR_LOD_MAPPING_H
#include "include/lang.h"

STRATA_NAMESPACE_BEGIN

// Points of one level sharing a UV that a mapping considers (X_1,v and X_2,v are bounded so); more
// refuse the mapping as ambiguous.
CONST_DEF uint LOD_MAX_CANDIDATES = 8u;
// UV-triangle area (in UV units) below which a triangle has no usable parametrisation.
CONST_DEF float LOD_MIN_UV_AREA = 1e-12f;
// Two candidates closer than this (object space, relative to the larger coordinate) are one point
// that the UV query reported twice (on the edge two triangles share).
CONST_DEF float LOD_SAME_POINT = 1e-5f;

// Twice the area of a UV triangle.
INLINE float uv_double_area(vec2 t0, vec2 t1, vec2 t2) {
  vec2 a = t1 - t0;
  vec2 b = t2 - t0;
  return abs(a.x * b.y - a.y * b.x);
}

// |u_i x v_i| of LOD Eq. 6 on a triangle (positions p, UVs t): the surface area per unit UV area,
// constant over the triangle (the UV map is affine on it). 0 for a degenerate UV triangle.
INLINE float area_per_uv_area(vec3 p0, vec3 p1, vec3 p2, vec2 t0, vec2 t1, vec2 t2) {
  float uv2 = uv_double_area(t0, t1, t2);
  if (!(uv2 > 2.0f * LOD_MIN_UV_AREA)) return 0.0f;
  float area = length(cross(p1 - p0, p2 - p0));
  float r = area / uv2;
  return isinf(r) || isnan(r) ? 0.0f : r;
}

// |d tau / dx| = |u_2 x v_2| / |u_1 x v_1|                               (LOD Eq. 6)
// 0 (the mapping fails) when either side is degenerate.
INLINE float lod_jacobian(float area_per_uv_from, float area_per_uv_to) {
  if (!(area_per_uv_from > 0.0f) || !(area_per_uv_to > 0.0f)) return 0.0f;
  float j = area_per_uv_to / area_per_uv_from;
  return isinf(j) || isnan(j) ? 0.0f : j;
}

// The same Jacobian in barycentric measure, as the surface resolver reports it: the render-space
// triangle areas of both points are in their SurfaceHit (the splat's area ratio and the
// reconnection's density), so the resolver's factor is what is left of Eq. 6,
//   |db_2/db_1| = A_uv(triangle 1) / A_uv(triangle 2),
// and (A_2 / A_1) |db_2/db_1| = (A_2 / A_uv,2) / (A_1 / A_uv,1) = |d tau / dx|.
INLINE float lod_bary_jacobian(float uv_double_area_from, float uv_double_area_to) {
  if (!(uv_double_area_from > 2.0f * LOD_MIN_UV_AREA) || !(uv_double_area_to > 2.0f * LOD_MIN_UV_AREA)) return 0.0f;
  float j = uv_double_area_from / uv_double_area_to;
  return isinf(j) || isnan(j) ? 0.0f : j;
}

INLINE bool same_lod_point(vec3 a, vec3 b) {
  vec3 d = abs(a - b);
  float scale = max(1.0f, max(max(abs(a.x), abs(a.y)), abs(a.z)));
  return max(max(d.x, d.y), d.z) <= LOD_SAME_POINT * scale;
}

// LOD Alg. 1: greedy matching of X_1,v (`from`, n_from points) and X_2,v (`to`, n_to points) by
// distance; returns the index in `to` matched with from[which], or -1 when it stays unmatched
// (X_2,v ran out first). Pairs are taken in order of distance, ties by (from, to) index, so that the
// inverse mapping, which matches the same sets the other way round, pairs the same points: tau stays
// a bijection on what it maps.
INLINE int lod_match(vec3 from[LOD_MAX_CANDIDATES], uint n_from, vec3 to[LOD_MAX_CANDIDATES], uint n_to, uint which) {
  uint used_from = 0u;
  uint used_to = 0u;
  uint rounds = min(n_from, n_to);
  for (uint round = 0u; round < rounds; ++round) {
    float best = 3.4e38f;
    uint bi = 0u;
    uint bj = 0u;
    for (uint i = 0u; i < n_from; ++i) {
      if ((used_from & (1u << i)) != 0u) continue;
      for (uint j = 0u; j < n_to; ++j) {
        if ((used_to & (1u << j)) != 0u) continue;
        vec3 d = from[i] - to[j];
        float dist2 = dot(d, d);
        if (dist2 < best) {
          best = dist2;
          bi = i;
          bj = j;
        }
      }
    }
    if (bi == which) return int(bj);
    used_from |= 1u << bi;
    used_to |= 1u << bj;
  }
  return -1;
}

// How a surface resolution went across a LoD switch (ResolvedSurface.lod_mapping; the counters
// COUNTER_LOD_*).
CONST_DEF uint LOD_MAPPING_NONE = 0u;      // same level: triangle and barycentrics kept (LOD 4.4, "Optimizations")
CONST_DEF uint LOD_MAPPED_UNIQUE = 1u;     // one point on each side shares the UV
CONST_DEF uint LOD_MAPPED_MATCHED = 2u;    // several did; Alg. 1 paired them
CONST_DEF uint LOD_FAIL_OFF = 3u;          // mapping off (for this kind of vertex): the shift fails as stale
CONST_DEF uint LOD_FAIL_OUTSIDE = 4u;      // no point of the target level has this UV
CONST_DEF uint LOD_FAIL_AMBIGUOUS = 5u;    // several points share the UV and matching is off, it left the
                                           // point unmatched, or more than LOD_MAX_CANDIDATES share it
CONST_DEF uint LOD_FAIL_DEGENERATE = 6u;   // a degenerate UV triangle on either side

// GpuLodTable.mode, .vertices (session options lod_mapping, lod_vertices)
CONST_DEF uint LOD_MODE_OFF = 0u;
CONST_DEF uint LOD_MODE_UV = 1u;
CONST_DEF uint LOD_VERTEX_PRIMARY = 1u;       // the primary hit x_1 (splat reprojection, gather backprojection)
CONST_DEF uint LOD_VERTEX_RECONNECTION = 2u;  // the reconnection vertex x_k (and a replayed light point)
CONST_DEF uint LOD_MAX_LEVELS = 8u;           // levels a mapping reaches (the UV TLAS's 8-bit instance mask)

// The LoD table (BINDING_LOD_TABLE): a header, then one entry per instance.
struct GpuLodHeader {
  uint mode;       // LOD_MODE_*
  uint matching;   // 1: Alg. 1 settles ambiguous UVs; 0: they refuse the mapping
  uint vertices;   // LOD_VERTEX_* bits: which vertices are mapped
  uint instances;  // entries that follow
};
struct GpuLodInstance {
  uint levels;    // LoD levels that have a UV plane (0: the instance has one level, or is not mapped)
  uint uv_plane;  // its plane in the UV TLAS (z = 2 * uv_plane)
  uint pad0;
  uint pad1;
  uint primitive_base[LOD_MAX_LEVELS];  // per level: its mesh's first GpuPrimitive
};

STRATA_NAMESPACE_END

#ifdef __cplusplus
static_assert(sizeof(strata::gpu::GpuLodHeader) == 16);
static_assert(sizeof(strata::gpu::GpuLodInstance) == 16 + 4 * strata::gpu::LOD_MAX_LEVELS);
#endif
#endif
