#pragma once
// The light tree of a frame (include/light_tree_data.h, sampling/light_tree.h; docs/ARCHITECTURE.md,
// "Light sampling"): built on the host from the frame's light table, every frame, in render space,
// and written to the device as one buffer per history slot, so that either frame's passes choose
// lights and evaluate their probabilities with that frame's tree.
#include <cstddef>
#include <span>
#include <vector>

#include <glm/glm.hpp>

#include "include/light_tree_data.h"
#include "render/emitters.h"
#include "scene/scene.h"

namespace strata::render {

struct LightTree {
  std::vector<gpu::GpuLightNode> nodes;   // depth-first; the root at 0
  std::vector<glm::uvec4> trails;         // per table entry (GpuLightTreeHeader::trails_offset)
  std::vector<glm::uvec2> directional;    // (entry, probability among the directional lights as float bits)
  float directional_prob = 0.0f;
  std::vector<glm::uvec2> instances;      // per instance: first geometry record, geometry count
  std::vector<glm::uvec2> geometries;     // (first entry, entry count)
  std::vector<uint32_t> triangles;        // per emitter entry: its triangle
  uint32_t entry_count = 0;

  // The device buffer: the header with its offsets, then the arrays, each at a multiple of 16 bytes.
  std::vector<std::byte> bytes() const;
  // The table entry of an emitter triangle (LIGHT_TREE_NONE where the table has none), as the
  // passes look it up.
  uint32_t entry_of(uint32_t instance, uint32_t geometry, uint32_t triangle) const;
};

// The tree over `table`'s entries with positive power: an emitter's bounds are its triangle, its
// cone its normal (theta_o 0, theta_e pi/2; two-sided for a double-sided material); a point light
// is a point emitting everywhere (theta_o pi), a spot light a point whose cone is its axis and outer
// angle. Directional lights stay out of the tree, chosen with their share of the table's power.
// Splits minimise power x orientation measure x size over 12 bins on each axis (Conty Estevez &
// Kulla 2018, Sec. 4.4), by count past depth 40 (so a trail fits 64 bits).
LightTree build_light_tree(const EmitterTable& table, std::span<const scene::Light> lights, uint32_t instance_count);

// sampling/light_tree.h on the host (tests): the entry chosen by u at x with its probability, and
// the probability of an entry; `receiver` the surface at x (sampling/light_tree.h, light_node_receiver).
bool light_tree_choose(const LightTree& tree, glm::vec3 x, glm::vec4 receiver, float u, uint32_t& entry, float& pmf);
float light_tree_pmf(const LightTree& tree, glm::vec3 x, glm::vec4 receiver, uint32_t entry);

}  // namespace strata::render
