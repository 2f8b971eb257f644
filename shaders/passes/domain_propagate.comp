#version 460
// Pass `domain_propagate` (stage domain_init; ML 4.3, Sec. 5): every previous domain (p, i) that
// propagates (the front layer's, and deep domains activated by propagation, not by hole filling)
// carries its representative hit c_{p,i} into this frame: T(c_{p,i}), the point kept in object
// space (the surface resolver), is projected through this frame's camera into pixel p', and its
// layer i' there is counted along the ray from the camera to it (ML Fig. 2: one closest-hit query
// per surface in front, front faces counted as restir/layer_data.h defines layers). A deep i' marks
// domain (p', i') with the instance of T(c)'s immediate occluder, which domain_build compares with
// the occluder of the domain's own representative hit (ML Sec. 5, footnote 2). A dormant domain
// (SPEC_DORMANT_LIST) keeps its layer and occluder without the walk (it was not about to be
// uncovered; the occluder check confirms it). A hit that lands on
// the front layer needs no mark (front domains are always active); one that falls outside the
// image, behind the camera, on a back face, or deeper than the k layers is dropped. One thread per
// previous domain: the image dispatch the front layer's, the list dispatch (SPEC_DOMAIN_LIST) the
// previous frame's active deep domains and, with SPEC_DORMANT_LIST, its dormant ones (the silhouette
// band, domain_fill.comp; restir/domain_list_prev.glsl).
#extension GL_EXT_ray_query : require
#extension GL_GOOGLE_include_directive : require

layout(local_size_x = 8, local_size_y = 8, local_size_z = 1) in;

#define STRATA_HISTORY 1
#include "include/scene_bridge.glsl"
#include "restir/restir_pass.glsl"
#include "restir/layers.glsl"
#include "restir/projection.glsl"
#include "restir/domain_list_prev.glsl"

layout(set = 0, binding = BINDING_PRIMARY_PREV, std430) readonly buffer PrimaryPrev { GpuPrimaryHit b_primary_prev[]; };
layout(set = 0, binding = BINDING_PRIMARY, std430) readonly buffer Primary { GpuPrimaryHit b_primary[]; };
#include "restir/seen_in_pixel.glsl"
layout(set = 0, binding = BINDING_DOMAIN_MARKS, std430) buffer Marks { GpuDomainMark b_marks[]; };

void main() {
  uint d;
  if (k_domain_list) {
    if (!prev_list_entry(d)) return;
  } else {
    uvec2 prev_pixel = gl_GlobalInvocationID.xy;
    if (prev_pixel.x >= u_frame.prev_width || prev_pixel.y >= u_frame.prev_height) return;
    d = prev_domain_of(prev_pixel, 0u);
  }
  if ((b_domains_prev[d].flags & DOMAIN_PROPAGATES) == 0u) return;
  SurfacePoint c = primary_surface(b_primary_prev[d]);
  ResolvedSurface moved = resolve_surface(false, c);  // T(c_{p,i})
  if (moved.reason != RESOLVE_OK) return;
  vec3 origin = u_frame.camera.position.xyz;  // the lens centre at the frame's instant
  vec3 e = moved.hit.position - origin;
  float dist = length(e);
  uvec2 pixel;
  vec2 sub;
  if (!(dist > 0.0) || !project(u_frame.camera, u_frame.width, u_frame.height, moved.hit.position, origin, pixel, sub)) return;
  vec3 dir = e / dist;
  if (dot(moved.hit.geo_normal, dir) >= 0.0) return;  // a back face is in no layer
  // Layer 0 without a walk (most front-layer hits stay in front): front domains need no mark.
  if (seen_in_pixel(false, pixel, c.instance, dist)) return;
  uint found;
  uint occluder;
  if (k_dormant_list) {
    // A dormant domain is not about to be uncovered (the reveal prediction or the silhouette band):
    // it keeps its layer and its immediate occluder instead of counting them along the ray, and
    // domain_build's occluder check confirms the occluder at its new pixel (ML Sec. 5, footnote 2).
    found = prev_domain_layer_of(d);
    occluder = b_domains_prev[d].occluder;
  } else {
    LayerWalk w = walk_to_point(false, origin, dir, c, dist);  // ML Fig. 2
    counter_add(COUNTER_RAYS_DOMAIN_INIT, w.rays);
    found = w.layer;
    occluder = w.occluder;
  }
  if (found == 0u || found >= u_restir.layers) return;
  uint target = domain_of(pixel, found);
  atomicMin(b_marks[target].occluder_min, occluder);
  atomicMin(b_marks[target].occluder_max, ~occluder);  // the greatest occluder, as the least complement
}
