#include "scene/builtin/common.h"

#include <algorithm>
#include <cmath>

#include <glm/gtc/matrix_transform.hpp>

#include "scene/animation.h"
#include "scene/triangle_order.h"
#include "scene/transform.h"

namespace strata::scene::builtin {

float key_time(uint32_t frame) {
  return frame_time(frame, kFramesPerSecond);
}

glm::quat look_at(const glm::vec3& eye, const glm::vec3& target, const glm::vec3& up) {
  return glm::normalize(glm::quatLookAtRH(glm::normalize(target - eye), up));
}

Light light_at(const std::string& name, LightType type, glm::vec3 color, float intensity, glm::vec3 position,
               glm::vec3 direction) {
  Light l;
  l.name = name;
  l.type = type;
  l.color = color;
  l.intensity = intensity;
  // Straight up or down, +Y cannot be the up vector: -Z is.
  const glm::vec3 up = std::abs(glm::normalize(direction).y) > 0.9f ? glm::vec3(0, 0, -1) : glm::vec3(0, 1, 0);
  l.transform = glm::translate(glm::mat4(1.0f), position) * glm::mat4_cast(look_at(position, position + direction, up));
  return l;
}

glm::mat4 compose_key(const TransformKey& key) {
  return compose_trs(key);
}

SceneBuilder::SceneBuilder(std::string name) {
  scene_.name = std::move(name);
  scene_.animation.frames_per_second = kFramesPerSecond;
}

uint32_t SceneBuilder::material(const std::string& name, glm::vec3 base_color, float metallic,
                                float roughness) {
  Material m;
  m.name = name;
  m.base_color = base_color;
  m.metallic = metallic;
  m.roughness = roughness;
  scene_.materials.push_back(m);
  return static_cast<uint32_t>(scene_.materials.size() - 1);
}

uint32_t SceneBuilder::matte(const std::string& name, glm::vec3 base_color) {
  const uint32_t index = material(name, base_color, 0.0f, 1.0f);
  scene_.materials[index].specular = 0.0f;
  return index;
}

uint32_t SceneBuilder::emitter(const std::string& name, glm::vec3 radiance, bool double_sided) {
  const uint32_t index = matte(name, glm::vec3(0.78f));
  scene_.materials[index].emission = radiance;
  scene_.materials[index].double_sided = double_sided;
  return index;
}

uint32_t SceneBuilder::mesh(const std::string& name, std::vector<Primitive> primitives) {
  scene_.meshes.push_back(Mesh{name, std::move(primitives)});
  return static_cast<uint32_t>(scene_.meshes.size() - 1);
}

uint32_t SceneBuilder::instance(const std::string& name, std::vector<uint32_t> lod_meshes,
                                const glm::mat4& transform, uint32_t lod) {
  scene_.instances.push_back(Instance{name, std::move(lod_meshes), transform, lod});
  return static_cast<uint32_t>(scene_.instances.size() - 1);
}

uint32_t SceneBuilder::instance(const std::string& name, uint32_t mesh,
                                const glm::mat4& transform) {
  return instance(name, std::vector<uint32_t>{mesh}, transform, 0);
}

void SceneBuilder::camera(const glm::vec3& eye, const glm::vec3& target, float yfov) {
  scene_.camera.position = eye;
  scene_.camera.orientation = look_at(eye, target);
  scene_.camera.yfov = yfov;
  scene_.camera.focus_distance = glm::length(target - eye);
}

void SceneBuilder::still_camera() {
  const Camera& c = scene_.camera;
  scene_.animation.camera = {CameraKey{key_time(0), c.position, c.orientation},
                             CameraKey{key_time(kFrameCount - 1), c.position, c.orientation}};
}

void SceneBuilder::lod_key(uint32_t frame, uint32_t instance, uint32_t level) {
  scene_.animation.lod_schedule.push_back(LodKey{key_time(frame), instance, level});
}

uint32_t SceneBuilder::light(Light light) {
  scene_.lights.push_back(std::move(light));
  return static_cast<uint32_t>(scene_.lights.size() - 1);
}

Scene SceneBuilder::finish() {
  auto& schedule = scene_.animation.lod_schedule;
  std::stable_sort(schedule.begin(), schedule.end(),
                   [](const LodKey& a, const LodKey& b) { return a.time < b.time; });
  auto& tracks = scene_.animation.tracks;
  std::stable_sort(
      tracks.begin(), tracks.end(),
      [](const InstanceTrack& a, const InstanceTrack& b) { return a.instance < b.instance; });
  sort_triangles_spatially(scene_);
  return std::move(scene_);
}

}  // namespace strata::scene::builtin
