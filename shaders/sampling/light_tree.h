// The light tree's choice of a light at a shading point and that choice's probability (one
// definition for the passes and the host's tests; include/light_tree_data.h has the layout).
// Before including, define how a tree is read:
//   LIGHT_TREE_T                 the type of a tree handle (a buffer address, a host view)
//   LIGHT_TREE_NODE(tree, i)     its GpuLightNode i
//   LIGHT_TREE_TRAIL(tree, e)    the trail (uvec4) of table entry e
//   LIGHT_TREE_NODE_COUNT(tree)  its node count
#ifndef STRATA_LIGHT_TREE_H
#define STRATA_LIGHT_TREE_H
#include "include/lang.h"
#include "include/light_tree_data.h"
#include "sampling/warp.h"

STRATA_NAMESPACE_BEGIN

// How far below its bound a cosine still counts as inside, so that float rounding of the bounds
// never culls a light that reaches x; and the least cosine factor of a node not culled.
CONST_DEF float LIGHT_TREE_COS_SLACK = 1e-3f;
CONST_DEF float LIGHT_TREE_MIN_COS = 1e-3f;

// The receiver's factor of a node's importance at x, for a receiver r: r.xyz the geometric normal
// of the surface at x on the side the path arrives from (vec3(0): no surface), r.w 1 to weigh by
// the cosine at the receiver (Conty Estevez & Kulla 2018, Eq. 3's cos theta_i), 0 not to.
// 0 where the node's box lies wholly behind the surface, where every method's scattering is 0
// (reflection only: scatter() and path_trace.comp test the geometric normal): the largest normal
// component of y - x over the box, a linear function, is negative by more than float rounding
// (LIGHT_TREE_COS_SLACK). Else, weighed, that component over the least distance to the box, a
// bound of the cosine: it fits an integrand that carries the cosine (a rough surface), not a
// glossy lobe, whose f cos theta_i does not fall with the cosine near the surface's plane (on glass
// seen at a grazing angle, a point light's highlight comes from a light there, and the weight made
// it a rare pick of huge value: docs/BENCHMARKS.md, "Many lights"); so bsdf_light_receiver
// (material/bsdf.h) weighs only rough surfaces.
// `to_centre`: from x to the box's centre; `half_extent`: half the box's size.
INLINE float light_node_receiver(vec3 half_extent, vec3 to_centre, vec4 r) {
  vec3 nrm = vec3(r.x, r.y, r.z);
  if (!(dot(nrm, nrm) > 0.0f)) return 1.0f;
  float top = dot(nrm, to_centre) + dot(abs(nrm), half_extent);
  if (top < 0.0f) {
    vec3 reach = abs(to_centre) + half_extent;
    return top / sqrt(dot(reach, reach)) <= -LIGHT_TREE_COS_SLACK ? 0.0f : LIGHT_TREE_MIN_COS;
  }
  if (!(r.w > 0.0f)) return 1.0f;
  vec3 gap = max(abs(to_centre) - half_extent, vec3(0.0f));
  float near2 = dot(gap, gap);
  return near2 > 0.0f ? clamp(top / sqrt(near2), LIGHT_TREE_MIN_COS, 1.0f) : 1.0f;
}

// The importance of a node at shading point x with receiver r (Conty Estevez & Kulla 2018,
// Eq. 3): its power over the squared distance to its bounds' centre (no less than the bounds'
// squared radius, so x inside or beside them sees them all as near), times the cosine of
// theta' = max(0, theta_w - theta_o - theta_b), the least angle between an emitter normal of the
// cone and the direction to x that the bounds allow (theta_w: axis to x; theta_b: half the angle
// the bounds subtend), and 0 where theta' is past theta_e (no light below emits towards x); times
// the receiver's factor (light_node_receiver). Positive wherever some light below can reach x and
// be scattered there, which is what keeps the estimator unbiased. The angle differences by their
// cosines and sines (cos(a - b) = cos a cos b + sin a sin b), no inverse trigonometry.
INLINE float light_node_importance(GpuLightNode n, vec3 x, vec4 r) {
  float power = n.lo_power.w;
  if (!(power > 0.0f)) return 0.0f;
  vec3 lo = vec3(n.lo_power.x, n.lo_power.y, n.lo_power.z);
  vec3 hi = vec3(n.hi_cos_o.x, n.hi_cos_o.y, n.hi_cos_o.z);
  vec3 half_extent = 0.5f * (hi - lo);
  vec3 d = x - (lo + half_extent);
  float receiver = light_node_receiver(half_extent, -d, r);
  if (!(receiver > 0.0f)) return 0.0f;
  float r2 = dot(half_extent, half_extent);
  float d2 = dot(d, d);
  float dist2 = max(max(d2, r2), 1e-20f);
  if (d2 <= r2) return power * receiver / dist2;  // x within the bounding sphere: every orientation can face it
  vec3 axis = vec3(n.axis_cos_e.x, n.axis_cos_e.y, n.axis_cos_e.z);
  float cos_w = clamp(dot(axis, d) / sqrt(d2), -1.0f, 1.0f);
  if ((n.links.y & LIGHT_NODE_TWO_SIDED) != 0u) cos_w = abs(cos_w);
  float sin_w = sqrt(max(0.0f, 1.0f - cos_w * cos_w));
  // theta_x = max(0, theta_w - theta_o)
  float cos_o = n.hi_cos_o.w, sin_o = uintBitsToFloat(n.links.z);
  bool inside_o = cos_w >= cos_o;
  float cos_x = inside_o ? 1.0f : cos_w * cos_o + sin_w * sin_o;
  float sin_x = inside_o ? 0.0f : sin_w * cos_o - cos_w * sin_o;
  // theta' = max(0, theta_x - theta_b), sin^2 theta_b = r^2 / d^2
  float sin_b2 = r2 / d2;
  float cos_b = sqrt(max(0.0f, 1.0f - sin_b2));
  float cos_p = cos_x >= cos_b ? 1.0f : cos_x * cos_b + sin_x * sqrt(sin_b2);
  if (cos_p <= n.axis_cos_e.w - LIGHT_TREE_COS_SLACK) return 0.0f;
  return power * max(cos_p, LIGHT_TREE_MIN_COS) * receiver / dist2;
}

// The probabilities of interior node `node`'s first and second child at x: each one's importance
// over both children's (0 where neither reaches x).
INLINE vec2 light_child_probabilities(LIGHT_TREE_T tree, uint node, vec3 x, vec4 r) {
  GpuLightNode n = LIGHT_TREE_NODE(tree, node);
  float i0 = light_node_importance(LIGHT_TREE_NODE(tree, node + 1u), x, r);
  float i1 = light_node_importance(LIGHT_TREE_NODE(tree, n.links.x), x, r);
  float sum = i0 + i1;
  if (!(sum > 0.0f) || isinf(sum)) return vec2(0.0f);
  return vec2(i0 / sum, i1 / sum);
}

// Descends the tree from the root at x (receiver r, light_node_receiver) with u in [0, 1): at each
// node the first child where u falls below its probability (u rescaled to the chosen part), else
// the second. The table entry of the leaf reached, and the product of the choices' probabilities;
// false where no light reaches x.
INLINE bool light_tree_choose(LIGHT_TREE_T tree, vec3 x, vec4 r, float u, OUT(uint) entry, OUT(float) pmf) {
  entry = LIGHT_TREE_NONE;
  pmf = 1.0f;
  if (LIGHT_TREE_NODE_COUNT(tree) == 0u) return false;
  uint node = 0u;
  for (uint depth = 0u; depth <= LIGHT_TREE_MAX_DEPTH; ++depth) {
    GpuLightNode n = LIGHT_TREE_NODE(tree, node);
    if ((n.links.y & LIGHT_NODE_LEAF) != 0u) {
      entry = n.links.x;
      return pmf > 0.0f;
    }
    vec2 p = light_child_probabilities(tree, node, x, r);
    if (u < p.x) {
      pmf *= p.x;
      u = min(u / p.x, 0.99999994f);
      node = node + 1u;
    } else {
      if (!(p.y > 0.0f)) return false;
      pmf *= p.y;
      u = min((u - p.x) / p.y, 0.99999994f);
      node = n.links.x;
    }
  }
  return false;
}

// The probability with which light_tree_choose reaches table entry e from x: the same products along
// its trail, in the same order (0 for an entry the tree does not hold).
INLINE float light_tree_pmf(LIGHT_TREE_T tree, vec3 x, vec4 r, uint e) {
  uvec4 trail = LIGHT_TREE_TRAIL(tree, e);
  if (trail.z == LIGHT_TREE_NONE) return 0.0f;
  float pmf = 1.0f;
  uint node = 0u;
  for (uint depth = 0u; depth < trail.z; ++depth) {
    bool second = (((depth < 32u ? trail.x >> depth : trail.y >> (depth - 32u)) & 1u) != 0u);
    vec2 p = light_child_probabilities(tree, node, x, r);
    pmf *= second ? p.y : p.x;
    if (!(pmf > 0.0f)) return 0.0f;
    node = second ? LIGHT_TREE_NODE(tree, node).links.x : node + 1u;
  }
  return pmf;
}

STRATA_NAMESPACE_END
#endif
