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

// The light table: emissive triangles, then the scene's punctual lights (light i at entry
// emitters.size() + i), with one alias table over both.
struct EmitterTable {
  std::vector<gpu::GpuEmitter> emitters;
  std::vector<gpu::GpuPunctualLight> lights;
  std::vector<gpu::GpuAliasEntry> alias;
  std::vector<double> power;  // per entry (emitters, then lights): its weight in the alias table
  double total_power = 0.0;  // sum of luminance(emission) * area * sides, plus the lights' punctual_power
};

// Emissive triangles of the frame's instances at their LoD levels, in render space (world minus
// `render_origin`), and the punctual lights where frame.lights puts them. Triangles of mirrored
// instances are re-wound so the cross product of their edges is the front-face normal.
// `scene_radius`: scene_bounding_radius, for the directional lights' power (render/punctual_lights.h).
EmitterTable build_emitter_table(const scene::Scene& scene, const scene::FrameState& frame, glm::dvec3 render_origin,
                                 double scene_radius = 1.0);

// Object-to-render transform: world transform with the origin moved, subtracting in double precision.
glm::mat4 object_to_render(const glm::mat4& object_to_world, glm::dvec3 render_origin);

}  // namespace strata::render
