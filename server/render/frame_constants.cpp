#include "render/frame_constants.h"

#include <cmath>

namespace strata::render {

gpu::GpuFrameConstants make_frame_constants(const scene::FrameState& frame, const scene::Environment& env,
                                            const GpuScene& scene, const FrameSetup& setup) {
  const auto& cam = frame.camera;
  float tan_half = std::tan(0.5f * cam.yfov);
  float aspect = float(setup.width) / float(setup.height);
  gpu::GpuFrameConstants c{};
  c.camera.forward = glm::vec4(cam.orientation * glm::vec3(0, 0, -1), 0);
  c.camera.right = glm::vec4(cam.orientation * glm::vec3(1, 0, 0) * (tan_half * aspect), 0);
  c.camera.up = glm::vec4(cam.orientation * glm::vec3(0, 1, 0) * tan_half, 0);
  c.camera.lens = glm::vec4(cam.aperture, cam.focus_distance, 0, 0);
  c.environment = glm::vec4(env.radiance, setup.env_nee ? 1.0f : 0.0f);
  c.width = setup.width;
  c.height = setup.height;
  c.frame_index = setup.frame_index;
  c.seed = setup.seed;
  c.samples_per_pixel = setup.spp;
  c.max_depth = setup.max_depth;
  c.emitter_count = scene.emitter_count();
  c.total_emitter_power = float(scene.total_emitter_power());
  // With both kinds of light, NEE splits its samples evenly between them.
  c.env_select_prob = !setup.env_nee ? 0.0f : (c.emitter_count == 0 ? 1.0f : 0.5f);
  return c;
}

}  // namespace strata::render
