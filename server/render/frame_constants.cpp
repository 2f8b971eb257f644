#include "render/frame_constants.h"

#include <algorithm>

#include <cmath>
#include <numbers>

namespace strata::render {
namespace {

// The probability that NEE picks the environment, given the light table's total power of the frame:
// none when it is not sampled; for a map its power's share (SceneEnvironment::power); for the
// constant environment, sampled only in scenes without emitters, all of them.
float env_select_prob(bool env_nee, const GpuScene& scene, double total_power) {
  if (!env_nee) return 0.0f;
  if (!scene.has_environment_map()) return 1.0f;
  const double env = scene.environment_power() / std::numbers::pi;  // in the light table's unit, power / pi
  return total_power > 0.0 ? float(env / (env + total_power)) : 1.0f;
}

}  // namespace

bool environment_nee(const scene::Environment& env, bool scene_has_emitters) {
  if (env.map) return SceneEnvironment::needed(env);  // a black map replaces the constant colour too
  return !scene_has_emitters && glm::any(glm::greaterThan(env.radiance, glm::vec3(0.0f)));
}

// The camera in its own frame's render space (its position is the origin).
gpu::GpuCamera make_camera(const scene::Camera& cam, uint32_t width, uint32_t height) {
  float tan_half = std::tan(0.5f * cam.yfov);
  float aspect = float(width) / float(height);
  gpu::GpuCamera c{};
  c.forward = glm::vec4(cam.orientation * glm::vec3(0, 0, -1), 0);
  c.right = glm::vec4(cam.orientation * glm::vec3(1, 0, 0) * (tan_half * aspect), 0);
  c.up = glm::vec4(cam.orientation * glm::vec3(0, 1, 0) * tan_half, 0);
  c.lens = glm::vec4(cam.aperture, cam.focus_distance, 0, 0);
  c.position = glm::vec4(0.0f);
  return c;
}

// The camera's motion over the frame's shutter relative to its closing camera (GpuShutter).
uint32_t time_partitions(const scene::FrameState& frame, uint32_t splats_per_frame) {
  return frame.camera_open ? std::max<uint32_t>(splats_per_frame, 1) : 1u;
}

gpu::GpuShutter make_shutter(const scene::FrameState& frame) {
  const scene::Camera& close = frame.camera;
  const scene::Camera open = frame.camera_open.value_or(close);
  gpu::GpuShutter s{};
  s.open_position = glm::vec4(open.position - close.position, frame.camera_open ? 1.0f : 0.0f);
  // The rotation turning the closing orientation into the opening one, shortest path (as slerp).
  glm::quat delta = glm::normalize(open.orientation * glm::conjugate(close.orientation));
  if (delta.w < 0.0f) delta = -delta;
  const glm::vec3 v(delta.x, delta.y, delta.z);
  const float sin_half = glm::length(v);
  s.rotation = sin_half > 1e-7f ? glm::vec4(v / sin_half, 2.0f * std::atan2(sin_half, delta.w)) : glm::vec4(0, 0, 1, 0);
  s.open_lens = glm::vec4(open.yfov, open.aperture, open.focus_distance, close.yfov);
  return s;
}

gpu::GpuFrameConstants make_frame_constants(const scene::FrameState& frame, const scene::Environment& env,
                                            const GpuScene& scene, const FrameSetup& setup) {
  gpu::GpuFrameConstants c{};
  c.camera = make_camera(frame.camera, setup.width, setup.height);
  c.shutter = make_shutter(frame);
  // A map replaces the constant colour (a black one too: the constant is then 0).
  c.environment = glm::vec4(env.map ? glm::vec3(0.0f) : env.radiance, setup.env_nee ? 1.0f : 0.0f);
  c.width = setup.width;
  c.height = setup.height;
  c.frame_index = setup.frame_index;
  c.seed = setup.seed;
  c.samples_per_pixel = setup.spp;
  c.max_depth = setup.max_depth;
  c.primary_mode = setup.fixed_primary ? gpu::PRIMARY_DOMAIN : gpu::PRIMARY_CENTRE;
  c.time_partitions = time_partitions(frame, setup.splats_per_frame);
  c.emitter_count = scene.emitter_count();
  c.total_emitter_power = float(scene.total_emitter_power());
  c.env_select_prob = env_select_prob(setup.env_nee, scene, scene.total_emitter_power());
  c.light_count = scene.light_count();
  c.lights = gpu::address_words(scene.lights_address(scene.parity()));
  // With history the other slot holds the previous frame's records; without, this frame's stand in.
  c.prev_lights = gpu::address_words(scene.lights_address(scene.keeps_history() ? 1 - scene.parity() : scene.parity()));
  c.environment_map = gpu::address_words(scene.environment_map_address());
  c.light_tree = gpu::address_words(scene.light_tree_address(scene.parity()));
  c.prev_light_tree = gpu::address_words(scene.light_tree_address(scene.keeps_history() ? 1 - scene.parity() : scene.parity()));

  // The previous frame (docs/ARCHITECTURE.md, State, session state): the one the scene's previous slot
  // holds, at the same resolution (a session's image size is fixed). After the first update that
  // is this frame itself, so the fields are consistent even where HISTORY_VALID is not set.
  const scene::FrameState& prev = scene.previous_frame();
  c.prev_camera = make_camera(prev.camera, setup.width, setup.height);
  c.prev_shutter = make_shutter(prev);
  c.prev_total_emitter_power = float(scene.prev_total_emitter_power());
  c.prev_env_select_prob = env_select_prob(setup.env_nee, scene, scene.prev_total_emitter_power());
  c.prev_width = setup.width;
  c.prev_height = setup.height;
  if (scene.history_valid() && !setup.history_held) {
    c.history_flags = gpu::HISTORY_VALID;
    if (scene.moved_since_previous()) c.history_flags |= gpu::HISTORY_SCENE_MOVED;
    if (scene.lights_reselected() || c.env_select_prob != c.prev_env_select_prob) c.history_flags |= gpu::HISTORY_LIGHTS_RESELECTED;
    if (scene.lights_moved()) c.history_flags |= gpu::HISTORY_LIGHTS_MOVED;
    if (scene.lights_changed() || c.env_select_prob != c.prev_env_select_prob) c.history_flags |= gpu::HISTORY_LIGHTS_CHANGED;
    if (frame.camera == prev.camera && frame.camera_open == prev.camera_open) c.history_flags |= gpu::HISTORY_CAMERA_STILL;
  }
  return c;
}

}  // namespace strata::render
