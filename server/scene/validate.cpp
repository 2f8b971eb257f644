// Scene::validate and Scene::triangle_count: the invariants every producer of a Scene (loaders,
// built-in generators, clients) must meet before the renderer sees it.
#include <algorithm>
#include <cmath>
#include <set>
#include <string>
#include <utility>

#include "scene/scene.h"

namespace strata::scene {
namespace {

std::string at(const std::string& array, size_t index) {
  return array + "[" + std::to_string(index) + "]";
}

[[noreturn]] void fail(const std::string& field, const std::string& what) {
  throw SceneError(field + " " + what);
}

void check_index(const std::string& field, uint64_t value, size_t count, const char* noun) {
  if (value >= count) {
    fail(field, "= " + std::to_string(value) + " is out of range (" + std::to_string(count) + " " +
                    noun + ")");
  }
}

void check_finite(const std::string& field, float value) {
  if (!std::isfinite(value)) fail(field, "is not finite");
}
template <int N>
void check_finite(const std::string& field, const glm::vec<N, float>& value) {
  for (int i = 0; i < N; ++i) {
    if (!std::isfinite(value[i])) fail(field, "is not finite");
  }
}
void check_finite(const std::string& field, const glm::quat& q) {
  check_finite(field, glm::vec4(q.x, q.y, q.z, q.w));
  if (glm::length(glm::vec4(q.x, q.y, q.z, q.w)) < 1e-6f) fail(field, "is a zero quaternion");
}
void check_finite(const std::string& field, const glm::mat4& m) {
  for (int c = 0; c < 4; ++c) check_finite(at(field, static_cast<size_t>(c)), m[c]);
}

void check_range(const std::string& field, float value, float lo, float hi) {
  check_finite(field, value);
  if (value < lo || value > hi) {
    fail(field, "= " + std::to_string(value) + " is outside [" + std::to_string(lo) + ", " +
                    std::to_string(hi) + "]");
  }
}

void validate_texture_ref(const std::string& field, const TextureRef& ref, size_t texture_count) {
  if (ref.texture < 0) return;
  check_index(field + ".texture", uint64_t(ref.texture), texture_count, "textures");
  if (ref.tex_coord > 1) fail(field + ".tex_coord", "= " + std::to_string(ref.tex_coord) + " is not 0 or 1");
  check_finite(field + ".transform.offset", ref.transform.offset);
  check_finite(field + ".transform.rotation", ref.transform.rotation);
  check_finite(field + ".transform.scale", ref.transform.scale);
}

void validate_textures(const TextureSet& t) {
  for (size_t i = 0; i < t.levels.size(); ++i) {
    const MipLevel& l = t.levels[i];
    if (l.width == 0 || l.height == 0 || uint64_t(l.offset) + uint64_t(l.width) * l.height > t.texels.size())
      fail(at("textures.levels", i), "lies outside textures.texels (" + std::to_string(t.texels.size()) + " texels)");
  }
  for (size_t i = 0; i < t.images.size(); ++i) {
    const TextureImage& image = t.images[i];
    if (image.level_count == 0 || uint64_t(image.first_level) + image.level_count > t.levels.size())
      fail(at("textures.images", i), "has levels outside textures.levels");
  }
  for (size_t i = 0; i < t.textures.size(); ++i)
    check_index(at("textures.textures", i) + ".image", t.textures[i].image, t.images.size(), "images");
}

void validate_material(const std::string& field, const Material& m) {
  for (int c = 0; c < 3; ++c) check_range(field + ".base_color", m.base_color[c], 0.0f, 1.0f);
  check_range(field + ".metallic", m.metallic, 0.0f, 1.0f);
  check_range(field + ".roughness", m.roughness, 0.0f, 1.0f);
  check_finite(field + ".emission", m.emission);
  if (glm::any(glm::lessThan(m.emission, glm::vec3(0.0f))))
    fail(field + ".emission", "is negative");
  check_range(field + ".alpha", m.alpha, 0.0f, 1.0f);
  check_finite(field + ".alpha_cutoff", m.alpha_cutoff);
  if (m.alpha_cutoff < 0.0f) fail(field + ".alpha_cutoff", "is negative");
  check_finite(field + ".normal_scale", m.normal_scale);
}

void check_count_of(const std::string& field, size_t count, size_t expected, const char* what) {
  if (count != expected)
    fail(field, "has " + std::to_string(count) + " entries, not one per " + what + " (" + std::to_string(expected) + ")");
}
void check_count(const std::string& field, size_t count, size_t vertices) {
  check_count_of(field, count, vertices, "vertex");
}

// Joints and weights (both empty, or one per vertex) and morph targets (one delta per vertex).
void validate_deformation(const std::string& field, const Primitive& p) {
  const size_t n = p.positions.size();
  if (!p.joints.empty() || !p.weights.empty()) {
    check_count(field + ".joints", p.joints.size(), n);
    check_count(field + ".weights", p.weights.size(), n);
  }
  for (size_t i = 0; i < p.weights.size(); ++i) check_finite(at(field + ".weights", i), p.weights[i]);
  for (size_t t = 0; t < p.targets.size(); ++t) {
    const std::string target = at(field + ".targets", t);
    check_count(target + ".positions", p.targets[t].positions.size(), n);
    if (!p.targets[t].normals.empty()) check_count(target + ".normals", p.targets[t].normals.size(), n);
    for (size_t i = 0; i < n; ++i) check_finite(at(target + ".positions", i), p.targets[t].positions[i]);
    for (size_t i = 0; i < p.targets[t].normals.size(); ++i)
      check_finite(at(target + ".normals", i), p.targets[t].normals[i]);
  }
}

void validate_primitive(const std::string& field, const Primitive& p, const std::vector<Material>& materials) {
  const size_t material_count = materials.size();
  const size_t n = p.positions.size();
  if (p.normals.size() != n) {
    fail(field + ".normals", "has " + std::to_string(p.normals.size()) +
                                 " entries, positions has " + std::to_string(n));
  }
  if (p.uvs.size() != n) {
    fail(field + ".uvs",
         "has " + std::to_string(p.uvs.size()) + " entries, positions has " + std::to_string(n));
  }
  if (p.indices.size() % 3 != 0) {
    fail(field + ".indices",
         "has " + std::to_string(p.indices.size()) + " entries, not a multiple of 3");
  }
  check_index(field + ".material", p.material, material_count, "materials");
  if (!p.uvs1.empty() && p.uvs1.size() != n)
    fail(field + ".uvs1", "has " + std::to_string(p.uvs1.size()) + " entries, positions has " + std::to_string(n));
  if (!p.tangents.empty() && p.tangents.size() != n)
    fail(field + ".tangents", "has " + std::to_string(p.tangents.size()) + " entries, positions has " + std::to_string(n));
  const Material& m = materials[p.material];
  for (const TextureRef* ref : {&m.base_color_texture, &m.metallic_roughness_texture, &m.normal_texture,
                                &m.emissive_texture}) {
    if (ref->texture >= 0 && ref->tex_coord == 1 && p.uvs1.size() != n)
      fail(field + ".uvs1", "is missing: materials[" + std::to_string(p.material) + "] reads texture coordinate set 1");
  }
  for (size_t i = 0; i < p.uvs1.size(); ++i) check_finite(at(field + ".uvs1", i), p.uvs1[i]);
  for (size_t i = 0; i < p.tangents.size(); ++i) check_finite(at(field + ".tangents", i), p.tangents[i]);
  for (size_t i = 0; i < p.indices.size(); ++i)
    check_index(at(field + ".indices", i), p.indices[i], n, "vertices");
  for (size_t i = 0; i < n; ++i) {
    check_finite(at(field + ".positions", i), p.positions[i]);
    check_finite(at(field + ".uvs", i), p.uvs[i]);
    check_finite(at(field + ".normals", i), p.normals[i]);
    if (std::abs(glm::length(p.normals[i]) - 1.0f) > 1e-3f)
      fail(at(field + ".normals", i), "is not unit length");
  }
  validate_deformation(field, p);
}

void validate_light(const std::string& field, const Light& l) {
  check_finite(field + ".color", l.color);
  if (glm::any(glm::lessThan(l.color, glm::vec3(0.0f)))) fail(field + ".color", "is negative");
  check_finite(field + ".intensity", l.intensity);
  if (l.intensity < 0.0f) fail(field + ".intensity", "is negative");
  check_finite(field + ".range", l.range);
  if (l.range < 0.0f) fail(field + ".range", "is negative");
  check_finite(field + ".transform", l.transform);
  if (l.type == LightType::kSpot) {
    check_range(field + ".outer_cone", l.outer_cone, 0.0f, 1.5707964f);
    check_range(field + ".inner_cone", l.inner_cone, 0.0f, 1.5707964f);
    if (!(l.inner_cone < l.outer_cone))
      fail(field + ".inner_cone", "= " + std::to_string(l.inner_cone) + " is not below outer_cone");
  }
}

void validate_camera(const Camera& c) {
  check_finite("camera.position", c.position);
  check_finite("camera.orientation", c.orientation);
  check_finite("camera.yfov", c.yfov);
  if (!(c.yfov > 0.0f && c.yfov < 3.14159265f))
    fail("camera.yfov", "= " + std::to_string(c.yfov) + " is outside (0, pi)");
  check_finite("camera.aperture", c.aperture);
  if (c.aperture < 0.0f) fail("camera.aperture", "is negative");
  check_finite("camera.focus_distance", c.focus_distance);
  if (c.focus_distance <= 0.0f) fail("camera.focus_distance", "is not positive");
}

template <typename Key>
void check_sorted(const std::string& field, const std::vector<Key>& keys) {
  for (size_t i = 0; i < keys.size(); ++i) {
    check_finite(at(field, i) + ".time", keys[i].time);
    if (i > 0 && keys[i].time < keys[i - 1].time)
      fail(at(field, i) + ".time", "is earlier than the key before it");
  }
}

void check_transform_keys(const std::string& field, const std::vector<TransformKey>& keys) {
  check_sorted(field, keys);
  for (size_t k = 0; k < keys.size(); ++k) {
    check_finite(at(field, k) + ".translation", keys[k].translation);
    check_finite(at(field, k) + ".rotation", keys[k].rotation);
    check_finite(at(field, k) + ".scale", keys[k].scale);
  }
}

// Joint tracks name a joint of a skin, morph tracks an instance with morph targets and one weight
// per target in every key; neither has a second track for the same joint or instance.
void validate_deform_tracks(const Scene& s) {
  const Animation& a = s.animation;
  std::set<std::pair<uint32_t, uint32_t>> joints;
  for (size_t t = 0; t < a.joint_tracks.size(); ++t) {
    const std::string field = at("animation.joint_tracks", t);
    const JointTrack& track = a.joint_tracks[t];
    check_index(field + ".skin", track.skin, s.skins.size(), "skins");
    check_index(field + ".joint", track.joint, s.skins[track.skin].joints.size(), "joints");
    if (!joints.insert({track.skin, track.joint}).second)
      fail(field, "is a second track for joint " + std::to_string(track.joint) + " of skins[" +
                      std::to_string(track.skin) + "]");
    check_transform_keys(field + ".keys", track.keys);
  }
  std::set<uint32_t> instances;
  for (size_t t = 0; t < a.morph_tracks.size(); ++t) {
    const std::string field = at("animation.morph_tracks", t);
    const MorphTrack& track = a.morph_tracks[t];
    check_index(field + ".instance", track.instance, s.instances.size(), "instances");
    const size_t targets = s.instances[track.instance].morph_weights.size();
    if (targets == 0) fail(field + ".instance", "= " + std::to_string(track.instance) + " has no morph targets");
    if (!instances.insert(track.instance).second)
      fail(field + ".instance", "= " + std::to_string(track.instance) + " has a second morph track");
    check_sorted(field + ".keys", track.keys);
    for (size_t k = 0; k < track.keys.size(); ++k) {
      const std::string key = at(field + ".keys", k) + ".weights";
      check_count_of(key, track.keys[k].weights.size(), targets, "morph target");
      for (size_t w = 0; w < targets; ++w) check_finite(at(key, w), track.keys[k].weights[w]);
    }
  }
}

void validate_animation(const Scene& s) {
  const Animation& a = s.animation;
  check_finite("animation.frames_per_second", a.frames_per_second);
  if (a.frames_per_second <= 0.0f) fail("animation.frames_per_second", "is not positive");
  check_sorted("animation.camera", a.camera);
  for (size_t i = 0; i < a.camera.size(); ++i) {
    check_finite(at("animation.camera", i) + ".position", a.camera[i].position);
    check_finite(at("animation.camera", i) + ".orientation", a.camera[i].orientation);
  }
  std::vector<bool> has_track(s.instances.size(), false);
  for (size_t t = 0; t < a.tracks.size(); ++t) {
    const std::string field = at("animation.tracks", t);
    const InstanceTrack& track = a.tracks[t];
    check_index(field + ".instance", track.instance, s.instances.size(), "instances");
    if (has_track[track.instance])
      fail(field + ".instance", "= " + std::to_string(track.instance) + " has a second track");
    has_track[track.instance] = true;
    check_transform_keys(field + ".keys", track.keys);
  }
  for (size_t t = 0; t < a.light_tracks.size(); ++t) {
    const std::string field = at("animation.light_tracks", t);
    check_index(field + ".light", a.light_tracks[t].light, s.lights.size(), "lights");
    check_transform_keys(field + ".keys", a.light_tracks[t].keys);
  }
  validate_deform_tracks(s);
  check_sorted("animation.lod_schedule", a.lod_schedule);
  for (size_t k = 0; k < a.lod_schedule.size(); ++k) {
    const std::string field = at("animation.lod_schedule", k);
    const LodKey& key = a.lod_schedule[k];
    check_index(field + ".instance", key.instance, s.instances.size(), "instances");
    check_index(field + ".level", key.level, s.instances[key.instance].lod_meshes.size(),
                "LoD levels");
  }
}

// Every primitive of a mesh has as many morph targets as the mesh has weights.
void validate_mesh_weights(const std::string& field, const Mesh& mesh) {
  for (size_t t = 0; t < mesh.weights.size(); ++t) check_finite(at(field + ".weights", t), mesh.weights[t]);
  for (size_t p = 0; p < mesh.primitives.size(); ++p) {
    check_count_of(at(field + ".primitives", p) + ".targets", mesh.primitives[p].targets.size(),
                   mesh.weights.size(), "weight of the mesh");
  }
}

void validate_skin(const std::string& field, const Skin& skin) {
  if (skin.joints.empty()) fail(field + ".joints", "is empty (a skin needs at least one joint)");
  check_count_of(field + ".inverse_bind", skin.inverse_bind.size(), skin.joints.size(), "joint");
  for (size_t j = 0; j < skin.joints.size(); ++j) {
    check_finite(at(field + ".inverse_bind", j), skin.inverse_bind[j]);
    check_finite(at(field + ".joints", j), skin.joints[j]);
  }
}

// A skinned instance's mesh has joints on every primitive, naming joints of its skin; a morphing
// instance has one weight per target of its mesh; a deforming instance has one LoD level.
void validate_instance_deformation(const std::string& field, const Instance& instance, const Scene& s) {
  if (instance.skin < -1 || instance.skin >= int64_t(s.skins.size()))
    fail(field + ".skin", "= " + std::to_string(instance.skin) + " is neither -1 nor a skin (" +
                              std::to_string(s.skins.size()) + " skins)");
  if (instance.deforms() && instance.lod_meshes.size() != 1)
    fail(field + ".lod_meshes", "has " + std::to_string(instance.lod_meshes.size()) +
                                    " LoD levels; a deforming instance has one");
  for (size_t l = 0; l < instance.lod_meshes.size(); ++l) {
    check_count_of(field + ".morph_weights", instance.morph_weights.size(),
                   s.meshes[instance.lod_meshes[l]].weights.size(),
                   ("morph target of " + at("meshes", instance.lod_meshes[l])).c_str());
  }
  for (size_t t = 0; t < instance.morph_weights.size(); ++t)
    check_finite(at(field + ".morph_weights", t), instance.morph_weights[t]);
  if (instance.skin < 0) return;
  const uint32_t mesh = instance.lod_meshes[0];
  const size_t joint_count = s.skins[size_t(instance.skin)].joints.size();
  for (size_t p = 0; p < s.meshes[mesh].primitives.size(); ++p) {
    const Primitive& primitive = s.meshes[mesh].primitives[p];
    const std::string joints = at(at("meshes", mesh) + ".primitives", p) + ".joints";
    if (primitive.joints.empty()) fail(joints, "is empty, but " + field + " skins the mesh");
    for (size_t v = 0; v < primitive.joints.size(); ++v) {
      const uint32_t top = std::max({primitive.joints[v].x, primitive.joints[v].y, primitive.joints[v].z,
                                     primitive.joints[v].w});
      if (top >= joint_count) {
        fail(at(joints, v), "names joint " + std::to_string(top) + ", but " + field + "'s skin, skins[" +
                                std::to_string(instance.skin) + "], has " + std::to_string(joint_count) + " joints");
      }
    }
  }
}

constexpr size_t kMaxPrimitivesPerMesh = 4096;
constexpr size_t kMaxInstances = (size_t(1) << 20) - 1;

}  // namespace

void Scene::validate() const {
  validate_textures(textures);
  for (size_t m = 0; m < materials.size(); ++m) {
    validate_material(at("materials", m), materials[m]);
    const Material& mat = materials[m];
    validate_texture_ref(at("materials", m) + ".base_color_texture", mat.base_color_texture, textures.textures.size());
    validate_texture_ref(at("materials", m) + ".metallic_roughness_texture", mat.metallic_roughness_texture,
                         textures.textures.size());
    validate_texture_ref(at("materials", m) + ".normal_texture", mat.normal_texture, textures.textures.size());
    validate_texture_ref(at("materials", m) + ".emissive_texture", mat.emissive_texture, textures.textures.size());
  }
  for (size_t m = 0; m < meshes.size(); ++m) {
    if (meshes[m].primitives.empty())
      fail(at("meshes", m) + ".primitives", "is empty (a mesh needs at least one primitive)");
    // A path sample stores the primitive in 12 bits (shaders/restir/reservoir.h).
    if (meshes[m].primitives.size() > kMaxPrimitivesPerMesh)
      fail(at("meshes", m) + ".primitives",
           "has " + std::to_string(meshes[m].primitives.size()) + " primitives; the limit is " +
               std::to_string(kMaxPrimitivesPerMesh) + " per mesh");
    for (size_t p = 0; p < meshes[m].primitives.size(); ++p) {
      validate_primitive(at(at("meshes", m) + ".primitives", p), meshes[m].primitives[p], materials);
    }
    validate_mesh_weights(at("meshes", m), meshes[m]);
  }
  for (size_t k = 0; k < skins.size(); ++k) validate_skin(at("skins", k), skins[k]);
  // Instance ids live in 20 bits of a path sample, all ones reserved (shaders/restir/reservoir.h).
  if (instances.size() > kMaxInstances)
    fail("instances", "has " + std::to_string(instances.size()) + " entries; the limit is " +
                          std::to_string(kMaxInstances));
  for (size_t i = 0; i < instances.size(); ++i) {
    const std::string field = at("instances", i);
    const Instance& instance = instances[i];
    if (instance.lod_meshes.empty())
      fail(field + ".lod_meshes", "is empty (an instance needs at least one mesh)");
    for (size_t l = 0; l < instance.lod_meshes.size(); ++l) {
      check_index(at(field + ".lod_meshes", l), instance.lod_meshes[l], meshes.size(), "meshes");
    }
    check_index(field + ".lod", instance.lod, instance.lod_meshes.size(), "LoD levels");
    check_finite(field + ".transform", instance.transform);
    validate_instance_deformation(field, instance, *this);
  }
  for (size_t l = 0; l < lights.size(); ++l) validate_light(at("lights", l), lights[l]);
  validate_camera(camera);
  check_finite("environment.radiance", environment.radiance);
  if (glm::any(glm::lessThan(environment.radiance, glm::vec3(0.0f))))
    fail("environment.radiance", "is negative");
  if (environment.map) {
    const EnvironmentMap& m = *environment.map;
    if (m.width == 0 || m.height == 0 || m.radiance.size() != size_t(m.width) * m.height)
      fail("environment.map.radiance", "does not hold width x height texels");
    if (m.conditional_cdf.size() != size_t(m.height) * (m.width + 1) || m.marginal_cdf.size() != size_t(m.height) + 1)
      fail("environment.map", "has sampling tables of the wrong size");
    check_finite("environment.map.intensity", m.intensity);
    if (m.intensity < 0.0f) fail("environment.map.intensity", "is negative");
    check_finite("environment.map.rotation", m.rotation);
  }
  validate_animation(*this);
}

size_t Scene::triangle_count() const {
  size_t count = 0;
  for (const Mesh& mesh : meshes) {
    for (const Primitive& primitive : mesh.primitives) count += primitive.triangle_count();
  }
  return count;
}

}  // namespace strata::scene
