// The light tree (docs/ARCHITECTURE.md, "Light sampling"): a bounding volume hierarchy over the light
// table's bounded entries (emissive triangles, point and spot lights) whose nodes carry the power,
// spatial bounds and orientation cone of the lights below them (Conty Estevez & Kulla 2018, "Importance
// Sampling of Many Lights with Adaptive Tree Splitting"). Next-event estimation descends it from the
// root, at each node choosing a child in proportion to its importance at the shading point
// (sampling/light_tree.h), so that near and facing lights are chosen more often than far or hidden
// ones; a light's probability is the product of the choices on its trail. Directional lights are
// unbounded and chosen apart, by power. One buffer per frame (render/light_tree.h writes it): this
// header, then the arrays at the byte offsets it names.
#ifndef STRATA_LIGHT_TREE_DATA_H
#define STRATA_LIGHT_TREE_DATA_H
#include "include/lang.h"

STRATA_NAMESPACE_BEGIN

// A node: its children are the next node (node + 1, depth-first order) and links.x; a leaf holds
// table entry links.x.
struct GpuLightNode {
  vec4 lo_power;       // xyz lower corner of the bounds (render space), w power (the light table's unit)
  vec4 hi_cos_o;       // xyz upper corner, w cos theta_o: theta_o the half-angle of the cone holding every emitter's normal
  vec4 axis_cos_e;     // xyz the cone's unit axis, w cos theta_e: theta_e how far from its normal an emitter emits
  uvec4 links;         // x second child or (leaf) entry, y LIGHT_NODE_* flags, z sin theta_o (float bits), w 0
};

CONST_DEF uint LIGHT_NODE_LEAF = 1u;
CONST_DEF uint LIGHT_NODE_TWO_SIDED = 2u;  // some emitter below emits from both faces
CONST_DEF uint LIGHT_TREE_NONE = 0xFFFFFFFFu;
CONST_DEF uint LIGHT_TREE_MAX_DEPTH = 64u;  // a trail's bits (render/light_tree.cpp splits by count past depth 40)

struct GpuLightTreeHeader {
  uint node_count;         // 0: no bounded light
  uint entry_count;        // the light table's entries (emitters, then punctual lights)
  uint directional_count;  // directional lights, chosen apart from the tree
  uint instance_count;
  float directional_prob;  // probability of choosing among the directional lights (else the tree)
  uint nodes_offset;       // byte offsets from the buffer's start: GpuLightNode[node_count]
  uint trails_offset;      // uvec4[entry_count]: x, y the trail's bits (1: second child) from the root, z its depth or LIGHT_TREE_NONE, w 0
  uint directional_offset; // uvec2[directional_count]: the light's table entry, its probability among them (float bits)
  uint instances_offset;   // uvec2[instance_count]: the instance's first geometry record and its geometry count (0 without emitters)
  uint geometries_offset;  // uvec2 per geometry of an emitting instance: its first table entry, its entry count
  uint triangles_offset;   // uint per emitter entry: its triangle (ascending within a geometry)
  uint pad0;
};

STRATA_NAMESPACE_END

#ifdef __cplusplus
static_assert(sizeof(strata::gpu::GpuLightNode) == 64);
static_assert(sizeof(strata::gpu::GpuLightTreeHeader) == 48);
#endif
#endif
