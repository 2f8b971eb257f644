#include "service/scene_analysis.h"

#include <algorithm>
#include <cmath>

#include "render/scene_environment.h"
#include "scene/unrendered.h"

namespace strata::service {
namespace {

uint64_t triangles_of(const scene::Scene& s, uint32_t mesh) {
  uint64_t n = 0;
  for (const auto& p : s.meshes.at(mesh).primitives) n += p.triangle_count();
  return n;
}

uint64_t emissive_triangles_of(const scene::Scene& s, uint32_t mesh) {
  uint64_t n = 0;
  for (const auto& p : s.meshes.at(mesh).primitives) {
    const auto& e = s.materials.at(p.material).emission;
    if (e.r > 0.0f || e.g > 0.0f || e.b > 0.0f) n += p.triangle_count();
  }
  return n;
}

float last_key_time(const scene::Animation& a) {
  float t = 0.0f;
  for (const auto& k : a.camera) t = std::max(t, k.time);
  for (const auto& track : a.tracks)
    for (const auto& k : track.keys) t = std::max(t, k.time);
  for (const auto& k : a.lod_schedule) t = std::max(t, k.time);
  return t;
}

}  // namespace

bool instance_emits(const scene::Scene& s, uint32_t id) {
  for (uint32_t mesh : s.instances.at(id).lod_meshes)
    if (emissive_triangles_of(s, mesh) > 0) return true;
  return false;
}

v1::SceneAnalysis analyze_scene(const scene::Scene& s) {
  v1::SceneAnalysis a;
  a.set_scene(s.name);
  a.set_triangles(s.triangle_count());
  uint32_t groups = 0;
  uint64_t emissive = 0;
  for (size_t i = 0; i < s.instances.size(); ++i) {
    const auto& inst = s.instances[i];
    auto* info = a.add_instances();
    info->set_id(uint32_t(i));
    info->set_name(inst.name);
    info->set_lod_levels(uint32_t(inst.lod_meshes.size()));
    info->set_lod(inst.lod);
    info->set_triangles(triangles_of(s, inst.lod_meshes.front()));
    if (inst.skin >= 0) info->set_joints(uint32_t(s.skins[size_t(inst.skin)].joints.size()));
    info->set_morph_targets(uint32_t(inst.morph_weights.size()));
    if (inst.lod_meshes.size() > 1) ++groups;
    emissive += emissive_triangles_of(s, inst.lod_meshes.at(std::min<size_t>(inst.lod, inst.lod_meshes.size() - 1)));
  }
  a.set_lod_groups(groups);
  for (size_t l = 0; l < s.lights.size(); ++l) {
    auto* info = a.add_lights();
    info->set_id(uint32_t(l));
    info->set_name(s.lights[l].name);
    const scene::LightType t = s.lights[l].type;
    info->set_type(t == scene::LightType::kPoint ? "point" : t == scene::LightType::kSpot ? "spot" : "directional");
  }
  a.set_emissive_triangles(emissive);
  const auto& env = s.environment.radiance;
  a.set_environment_light(s.environment.map ? render::SceneEnvironment::needed(s.environment)
                                            : (env.r > 0.0f || env.g > 0.0f || env.b > 0.0f));
  if (s.environment.map)
    a.set_environment_map(s.environment.map->name + " (" + std::to_string(s.environment.map->width) + " x " +
                          std::to_string(s.environment.map->height) + " texels)");
  a.set_thin_lens(s.camera.aperture > 0.0f);
  const bool moves = !s.animation.camera.empty() || !s.animation.tracks.empty() || !s.animation.lod_schedule.empty();
  const float fps = s.animation.frames_per_second;
  a.set_frames_per_second(fps);
  uint32_t frames = 1;
  if (moves && fps > 0.0f) frames = uint32_t(std::min(1e7f, std::floor(last_key_time(s.animation) * fps))) + 1;
  a.set_animation_frames(frames);
  for (const std::string& feature : scene::unrendered_features(s)) a.add_ignored(feature);
  return a;
}

}  // namespace strata::service
