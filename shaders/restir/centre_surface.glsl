// What the geometric filters of reuse compare (docs/ARCHITECTURE.md, "Spatial neighbours" and
// "Temporal history"): a pixel's centre hit from the visibility buffer, reduced to its shading normal,
// its distance and its material kind. The filters decide which domains take part from these alone,
// before any sample is looked at, so the MIS weights over the chosen domains stay unbiased.
#ifndef STRATA_CENTRE_SURFACE_GLSL
#define STRATA_CENTRE_SURFACE_GLSL

#include "material/bsdf.h"
#include "restir/reconnection.h"
#include "restir/thresholds.h"

struct CentreSurface {
  bool valid;   // the centre ray hit a surface that resolves in the frame asked for
  vec3 normal;  // shading normal
  float depth;  // distance along the centre ray
  uint kind;    // SURFACE_KIND_* bits of its material
};

CONST_DEF uint SURFACE_KIND_EMISSIVE = 1u;
CONST_DEF uint SURFACE_KIND_METAL = 2u;
CONST_DEF uint SURFACE_KIND_ROUGH = 4u;  // rough enough to reconnect (restir/reconnection.h)

// The SURFACE_KIND_* bits of a material (the primary stage stores them with each hit).
uint surface_kind(SurfaceMaterial m) {
  BsdfParams b = m.bsdf;
  return (material_emits(m) ? SURFACE_KIND_EMISSIVE : 0u) | (m.metallic >= 0.5 ? SURFACE_KIND_METAL : 0u) |
         (rough_vertex(b.alpha, max(b.f0.r, max(b.f0.g, b.f0.b))) ? SURFACE_KIND_ROUGH : 0u);
}

CentreSurface no_centre_surface(float depth) {
  CentreSurface c;
  c.valid = false;
  c.normal = vec3(0.0, 0.0, 1.0);
  c.depth = depth;
  c.kind = 0u;
  return c;
}

// A resolved surface point seen at distance `depth` by a camera of spread `spread` (camera_spread of
// the frame it was resolved in: its material's kind at its primary footprint, as the primary stage
// classifies its entries).
CentreSurface surface_of(ResolvedSurface r, float depth, float spread) {
  CentreSurface c = no_centre_surface(depth);
  if (r.reason != RESOLVE_OK) return c;
  c.valid = true;
  c.normal = r.hit.shading_normal;
  c.kind = surface_kind(material_at(r.hit, primary_footprint(spread, r.hit.position, dot(r.hit.geo_normal, normalize(r.hit.position)))));
  return c;
}

// The centre hit of a visibility-buffer entry in the entry's own frame, at its distance along the
// centre ray: what the primary stage stored with it (restir/primary_data.h), so no mesh is read.
CentreSurface centre_surface(GpuPrimaryHit h) {
  CentreSurface c = no_centre_surface(h.t);
  if ((h.flags & PRIMARY_HIT) == 0u) return c;
  c.valid = true;
  c.normal = h.shading_normal_kind.xyz;
  c.kind = floatBitsToUint(h.shading_normal_kind.w);
  return c;
}

// The filter: same kind, normals within 25 degrees, distances within 10% (restir/thresholds.h
// SPATIAL_*; the similarity test of Bitterli et al. 2020, section 6.1).
bool similar_surface(CentreSurface c, CentreSurface n) {
  return n.valid && n.kind == c.kind && dot(c.normal, n.normal) >= SPATIAL_MIN_NORMAL_COS &&
         abs(n.depth - c.depth) <= SPATIAL_MAX_DEPTH_RELATIVE * c.depth;
}

#endif
