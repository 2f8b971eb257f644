// The light tree's side of the scene bridge's lights (include/scene_lights.glsl includes this file;
// docs/ARCHITECTURE.md, "Light sampling"): either frame's tree read by the device addresses of the
// frame constants, sampling/light_tree.h over it, the table entry of a hit emitter triangle, and
// the choice among the tree and the directional lights with its probability.
#ifndef STRATA_SCENE_LIGHT_TREE_GLSL
#define STRATA_SCENE_LIGHT_TREE_GLSL
#extension GL_EXT_buffer_reference : require
#extension GL_EXT_buffer_reference_uvec2 : require

#include "include/bindings.h"
#include "include/frame_data.h"
#include "include/light_tree_data.h"

// The light tree of either frame (SPEC_LIGHT_TREE), by the device addresses of the frame constants:
// its header, and the addresses of its arrays.
layout(constant_id = SPEC_LIGHT_TREE) const bool k_light_tree = false;
layout(buffer_reference, std430, buffer_reference_align = 16) readonly buffer LightTreeHeaderRef { GpuLightTreeHeader h; };
layout(buffer_reference, std430, buffer_reference_align = 16) readonly buffer LightTreeNodes { GpuLightNode nodes[]; };
layout(buffer_reference, std430, buffer_reference_align = 16) readonly buffer LightTreeUvec4s { uvec4 v[]; };
layout(buffer_reference, std430, buffer_reference_align = 8) readonly buffer LightTreeUvec2s { uvec2 v[]; };
layout(buffer_reference, std430, buffer_reference_align = 4) readonly buffer LightTreeUints { uint v[]; };

struct LightTreeRef {
  GpuLightTreeHeader h;
  uvec2 base;
};

// A 64-bit device address (two words) plus a byte offset.
uvec2 address_plus(uvec2 a, uint offset) {
  uint lo = a.x + offset;
  return uvec2(lo, a.y + (lo < a.x ? 1u : 0u));
}

LightTreeRef light_tree_of(bool prev) {
  LightTreeRef t;
  t.base = prev ? u_frame.prev_light_tree : u_frame.light_tree;
  t.h = LightTreeHeaderRef(t.base).h;
  return t;
}

#define LIGHT_TREE_T LightTreeRef
#define LIGHT_TREE_NODE(tree, i) LightTreeNodes(address_plus((tree).base, (tree).h.nodes_offset)).nodes[i]
#define LIGHT_TREE_TRAIL(tree, e) LightTreeUvec4s(address_plus((tree).base, (tree).h.trails_offset)).v[e]
#define LIGHT_TREE_NODE_COUNT(tree) ((tree).h.node_count)
#include "sampling/light_tree.h"

// The table entry of emitter triangle (instance, geometry, triangle) in a tree's light table
// (LIGHT_TREE_NONE where that frame has none): its instance's geometry record, then a binary
// search of the geometry's triangles.
uint light_tree_entry(LightTreeRef t, uint instance, uint geometry, uint triangle) {
  if (instance >= t.h.instance_count) return LIGHT_TREE_NONE;
  uvec2 inst = LightTreeUvec2s(address_plus(t.base, t.h.instances_offset)).v[instance];
  if (geometry >= inst.y) return LIGHT_TREE_NONE;
  uvec2 g = LightTreeUvec2s(address_plus(t.base, t.h.geometries_offset)).v[inst.x + geometry];
  LightTreeUints tris = LightTreeUints(address_plus(t.base, t.h.triangles_offset));
  uint lo = g.x, hi = g.x + g.y;  // the first entry whose triangle is >= `triangle` lies in [lo, hi]
  while (lo < hi) {
    uint mid = (lo + hi) / 2u;
    if (tris.v[mid] < triangle) lo = mid + 1u;
    else hi = mid;
  }
  return lo < g.x + g.y && tris.v[lo] == triangle ? lo : LIGHT_TREE_NONE;
}

// The probability that a tree's sampler picks table entry `entry` at x (`receiver`: the surface
// there, bsdf_light_receiver), given that it does not pick the environment: a directional light's share
// among them, else the tree's choice.
float light_tree_select(LightTreeRef t, vec3 x, vec4 receiver, uint entry) {
  if (entry == LIGHT_TREE_NONE) return 0.0;
  LightTreeUvec2s directional = LightTreeUvec2s(address_plus(t.base, t.h.directional_offset));
  for (uint i = 0u; i < t.h.directional_count; ++i)
    if (directional.v[i].x == entry) return t.h.directional_prob * uintBitsToFloat(directional.v[i].y);
  return (1.0 - t.h.directional_prob) * light_tree_pmf(t, x, receiver, entry);
}

// With the tree: what it chooses from v in [0, 1) at x with `receiver` (a directional light by power
// with directional_prob, else the tree's leaf), and the probability of that choice.
bool light_tree_sample(LightTreeRef t, vec3 x, vec4 receiver, float v, out uint entry, out float pmf) {
  entry = LIGHT_TREE_NONE;
  pmf = 0.0;
  if (v < t.h.directional_prob) {
    LightTreeUvec2s directional = LightTreeUvec2s(address_plus(t.base, t.h.directional_offset));
    float w = v / t.h.directional_prob, below = 0.0;
    for (uint i = 0u; i < t.h.directional_count; ++i) {
      float p = uintBitsToFloat(directional.v[i].y);
      if (w < below + p || i + 1u == t.h.directional_count) {
        entry = directional.v[i].x;
        pmf = t.h.directional_prob * p;
        return pmf > 0.0;
      }
      below += p;
    }
    return false;
  }
  float w = min((v - t.h.directional_prob) / (1.0 - t.h.directional_prob), 0.99999994);
  float p;
  if (!light_tree_choose(t, x, receiver, w, entry, p)) return false;
  pmf = (1.0 - t.h.directional_prob) * p;
  return pmf > 0.0;
}

#endif
