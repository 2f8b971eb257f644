#pragma once
// Shared vocabulary of the built-in scenes: a scene builder, the animation clock and a camera
// helper. Every built-in animation is kFrameCount frames at kFramesPerSecond.
#include <cstdint>
#include <string>
#include <vector>

#include <glm/glm.hpp>
#include <glm/gtc/quaternion.hpp>

#include "scene/scene.h"

namespace strata::scene::builtin {

inline constexpr uint32_t kFrameCount = 120;
inline constexpr float kFramesPerSecond = 30.0f;
inline constexpr float kPi = 3.14159265358979f;

// Time of frame `frame`, computed exactly as Scene::frame_state computes it, so keys placed on
// frames are hit exactly.
float key_time(uint32_t frame);

// Orientation of a camera at `eye` looking at `target` (cameras look down local -Z, +Y up).
glm::quat look_at(const glm::vec3& eye, const glm::vec3& target,
                  const glm::vec3& up = {0.0f, 1.0f, 0.0f});

// A punctual light at `position` whose local -Z (a spot's axis, a directional light's direction)
// points along `direction`.
Light light_at(const std::string& name, LightType type, glm::vec3 color, float intensity, glm::vec3 position,
               glm::vec3 direction);

// compose_trs (scene/transform.h), the composition Scene::frame_state uses.
glm::mat4 compose_key(const TransformKey& key);

// Collects materials, meshes and instances and hands out their indices.
class SceneBuilder {
 public:
  explicit SceneBuilder(std::string name);

  uint32_t material(const std::string& name, glm::vec3 base_color, float metallic = 0.0f,
                    float roughness = 1.0f);
  // Pure Lambert (KHR_materials_specular factor 0: no dielectric highlight).
  uint32_t matte(const std::string& name, glm::vec3 base_color);
  // Emitters are matte too.
  uint32_t emitter(const std::string& name, glm::vec3 radiance, bool double_sided = false);
  uint32_t mesh(const std::string& name, std::vector<Primitive> primitives);
  uint32_t instance(const std::string& name, std::vector<uint32_t> lod_meshes,
                    const glm::mat4& transform, uint32_t lod = 0);
  uint32_t instance(const std::string& name, uint32_t mesh,
                    const glm::mat4& transform = glm::mat4(1.0f));

  void camera(const glm::vec3& eye, const glm::vec3& target, float yfov);
  // Camera keys on every frame from `path(frame)` -> (eye, target).
  template <typename Path>
  void camera_path(Path path);
  // A still camera: two equal keys spanning the animation (so its length stays 120 frames).
  void still_camera();
  // Track keys on every frame from `motion(frame)`; also sets the instance's rest transform to
  // the frame-0 key, so Instance::transform is what frame 0 shows.
  template <typename Motion>
  void track(uint32_t instance, Motion motion);
  void lod_key(uint32_t frame, uint32_t instance, uint32_t level);
  // Adds a punctual light; returns its index.
  uint32_t light(Light light);
  // Light keys on every frame from `motion(frame)` (a LightTrack); also sets the light's rest
  // transform to the frame-0 key, so Light::transform is what frame 0 shows.
  template <typename Motion>
  void light_track(uint32_t light, Motion motion);

  Scene& scene() { return scene_; }
  Scene finish();  // sorts the LoD schedule by time and tracks by instance

 private:
  // `motion(frame)` for every frame, each key at its frame's time.
  template <typename Motion>
  static std::vector<TransformKey> keys_of(Motion motion);
  Scene scene_;
};

template <typename Motion>
std::vector<TransformKey> SceneBuilder::keys_of(Motion motion) {
  std::vector<TransformKey> keys;
  for (uint32_t f = 0; f < kFrameCount; ++f) {
    TransformKey key = motion(f);
    key.time = key_time(f);
    keys.push_back(key);
  }
  return keys;
}

template <typename Path>
void SceneBuilder::camera_path(Path path) {
  scene_.animation.camera.clear();
  for (uint32_t f = 0; f < kFrameCount; ++f) {
    const auto [eye, target] = path(f);
    scene_.animation.camera.push_back(CameraKey{key_time(f), eye, look_at(eye, target)});
  }
  scene_.camera.position = scene_.animation.camera.front().position;
  scene_.camera.orientation = scene_.animation.camera.front().orientation;
}

template <typename Motion>
void SceneBuilder::track(uint32_t instance, Motion motion) {
  InstanceTrack track{instance, keys_of(motion)};
  scene_.instances[instance].transform = compose_key(track.keys.front());
  scene_.animation.tracks.push_back(std::move(track));
}

template <typename Motion>
void SceneBuilder::light_track(uint32_t light, Motion motion) {
  LightTrack track{light, keys_of(motion)};
  scene_.lights[light].transform = compose_key(track.keys.front());
  scene_.animation.light_tracks.push_back(std::move(track));
}

}  // namespace strata::scene::builtin
