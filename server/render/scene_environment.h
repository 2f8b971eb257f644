#pragma once
// A scene's environment map on the device (include/environment_data.h): the radiance (times the
// map's intensity) and the sampling tables of scene/environment_map.h, uploaded once per scene,
// read by the passes through the device address in the frame constants (no descriptor), and only
// for scenes that have a map: other scenes compile the constant environment (SPEC_ENV_MAP off).
#include "gpu/buffer.h"
#include "scene/scene.h"

namespace strata::render {

class SceneEnvironment {
 public:
  // The scene's environment has a map with some light in it (a black map is the black constant).
  static bool needed(const scene::Environment& env) { return env.map && env.map->weight_sum > 0.0 && env.map->intensity > 0.0f; }

  SceneEnvironment(const gpu::Context& ctx, const scene::EnvironmentMap& map);

  // Of the GpuEnvironmentMap record (GpuFrameConstants::environment_map).
  VkDeviceAddress address() const { return record_.address(); }
  VkDeviceSize bytes() const { return record_.size() + radiance_.size() + conditional_.size() + marginal_.size(); }

  // The power by which the light sampler weighs the map against the light table
  // (render/punctual_lights.h's units): pi L pi R^2, the irradiance a uniform environment of the
  // map's mean radiance L (over solid angle) gives a facing plane, over the scene's bounding disc
  // (R: scene_bounding_radius), as for a directional light.
  static double power(const scene::EnvironmentMap& map, double scene_radius);

 private:
  gpu::Buffer record_, radiance_, conditional_, marginal_;
};

}  // namespace strata::render
