#pragma once
// Next-event-estimation tables built on the host each frame: render-space emissive triangles and a
// Walker/Vose alias table that picks them in proportion to their power.
#include <span>
#include <vector>

#include <glm/glm.hpp>

#include "include/scene_data.h"
#include "scene/scene.h"

namespace strata::render {

// Alias table over non-negative weights; entries with all-zero weights select uniformly.
// Selecting column c uniformly, then c if coin < threshold else alias, gives P(i) = w_i / sum w.
std::vector<gpu::GpuAliasEntry> build_alias_table(std::span<const double> weights);

struct EmitterTable {
  std::vector<gpu::GpuEmitter> emitters;
  std::vector<gpu::GpuAliasEntry> alias;
  double total_power = 0.0;  // sum of luminance(emission) * area * sides
};

// Emissive triangles of the frame's instances at their LoD levels, in render space (world minus
// `render_origin`). Triangles of mirrored instances are re-wound so the cross product of their
// edges is the front-face normal.
EmitterTable build_emitter_table(const scene::Scene& scene, const scene::FrameState& frame, glm::dvec3 render_origin);

// Object-to-render transform: world transform with the origin moved, subtracting in double precision.
glm::mat4 object_to_render(const glm::mat4& object_to_world, glm::dvec3 render_origin);

}  // namespace strata::render
