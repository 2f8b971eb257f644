#pragma once
// KHR_lights_punctual on the device: a frame's light records in render space (GpuPunctualLight) and
// the power estimate by which the light table chooses them among the emissive triangles
// (docs/ARCHITECTURE.md, Light sampling).
#include <glm/glm.hpp>

#include "include/scene_data.h"
#include "scene/scene.h"

namespace strata::render {

// The radius of a sphere about the scene's instances at rest (frame 0's LoD levels): the extent over
// which a directional light's power is estimated. 1 for a scene without geometry.
double scene_bounding_radius(const scene::Scene& scene);

// The light's power as the light table weighs it (luminance of colour x intensity):
//   point        4 pi I
//   spot         2 pi I [(1 - c_f) + (c_f - c_o) / 3]: the solid angle of the cone weighted by the
//                square of the extension's falloff, c_o = cos(outer), c_f = c_o + 1 / scale where the
//                falloff reaches 1 (the ramp integrates to a third); (1 - c_o)^3 scale^2 / 3 when
//                c_f passes 1
//   directional  E pi R^2: the irradiance over the scene's bounding disc (R: scene_bounding_radius)
// `range` is left out (an overestimate of a windowed light). Any positive weight keeps the
// estimator unbiased; the closer to the light's share of the image, the lower its variance.
double punctual_power(const scene::Light& light, double scene_radius);

// The spot falloff's constants (KHR_lights_punctual's reference implementation):
// scale = 1 / max(0.001, cos(inner) - cos(outer)), offset = -cos(outer) scale.
glm::vec2 spot_angle_scale_offset(const scene::Light& light);

// The light at `light_to_world` (its node's world transform in the frame), in the render space of
// `render_origin`; intensity_pmf.w is left 0 for the light table to fill.
gpu::GpuPunctualLight punctual_record(const scene::Light& light, const glm::mat4& light_to_world, glm::dvec3 render_origin);

}  // namespace strata::render
