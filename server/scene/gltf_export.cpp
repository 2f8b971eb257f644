// export_glb: a Scene as one .glb that load_glb_bytes reads back equal (operator==) to it.
// Layout: node i is instance i (with `matrix`, or TRS plus extras.strata.rest_matrix when it is
// animated, as glTF forbids `matrix` on animated nodes), then the camera node; both are the
// scene's roots. Extra LoD levels are nodes outside the scene, named by the instance's MSFT_lod
// ids; then one node per punctual light (KHR_lights_punctual, its rest transform as `matrix`, or
// as an instance's when the light has a track); then per skin a skeleton node (a root) with its
// joints as children. Instance nodes carry their skin and morph weights (node.skin, node.weights).
// The default animation is one glTF animation: T/R/S channels per instance, light and joint track,
// a weights channel per morph track, T/R channels on the camera node. Textures, alpha modes and
// the environment map: gltf_export_textures.h; skins, joints, weights and morph targets:
// gltf_export_skins.h. Everything else strata needs rides in extras (see gltf_extras.h).
// Exactness: floats go into float accessors or into JSON as doubles (which read back exactly);
// an emission above 1 is split into emissiveFactor * emissiveStrength in double precision.
#include <algorithm>
#include <fstream>
#include <sstream>

#include <tiny_gltf.h>

#include "scene/gltf_export_builder.h"
#include "scene/gltf_export_skins.h"
#include "scene/gltf_extras.h"
#include "scene/scene_io.h"
#include "scene/transform.h"

namespace strata::scene {
namespace {

using gltf::doubles;
using gltf::GlbBuilder;
using gltf::kArray;
using gltf::kElements;
using gltf::kFloat;
using gltf::set_rest_transform;

constexpr const char* kLodExtension = "MSFT_lod";
constexpr const char* kEmissiveStrength = "KHR_materials_emissive_strength";
constexpr const char* kSpecular = "KHR_materials_specular";

void add_material(GlbBuilder& b, const Material& m) {
  tinygltf::Material out;
  out.name = m.name;
  out.pbrMetallicRoughness.baseColorFactor = {m.base_color.r, m.base_color.g, m.base_color.b, 1.0};
  out.pbrMetallicRoughness.metallicFactor = m.metallic;
  out.pbrMetallicRoughness.roughnessFactor = m.roughness;
  out.doubleSided = m.double_sided;
  const double peak = std::max({m.emission.r, m.emission.g, m.emission.b});
  const double scale = peak > 1.0 ? peak : 1.0;  // emissiveFactor must stay within [0, 1]
  out.emissiveFactor = {m.emission.r / scale, m.emission.g / scale, m.emission.b / scale};
  if (scale != 1.0) {
    out.extensions[kEmissiveStrength] =
        tinygltf::Value(tinygltf::Value::Object{{"emissiveStrength", tinygltf::Value(scale)}});
    b.use_extension(kEmissiveStrength);
  }
  if (m.specular != 1.0f) {
    out.extensions[kSpecular] =
        tinygltf::Value(tinygltf::Value::Object{{"specularFactor", tinygltf::Value(double(m.specular))}});
    b.use_extension(kSpecular);
  }
  std::vector<std::string> used;
  gltf::export_material_textures(m, out, used);
  for (const std::string& e : used) b.use_extension(e.c_str());
  b.model().materials.push_back(out);
}

tinygltf::Primitive primitive(GlbBuilder& b, const Primitive& p, const std::string& field) {
  tinygltf::Primitive out;
  out.mode = TINYGLTF_MODE_TRIANGLES;
  out.material = static_cast<int>(p.material);
  out.attributes["POSITION"] = b.accessor(p.positions, kFloat, TINYGLTF_TYPE_VEC3, 3, kArray, true);
  out.attributes["NORMAL"] = b.accessor(p.normals, kFloat, TINYGLTF_TYPE_VEC3, 3, kArray, false);
  out.attributes["TEXCOORD_0"] = b.accessor(p.uvs, kFloat, TINYGLTF_TYPE_VEC2, 2, kArray, false);
  // 16-bit indices when they fit (65535 itself is reserved for primitive restart).
  if (p.positions.size() < 65535) {
    std::vector<uint16_t> narrow(p.indices.size());
    std::transform(p.indices.begin(), p.indices.end(), narrow.begin(),
                   [](uint32_t i) { return static_cast<uint16_t>(i); });
    out.indices = b.accessor(narrow, TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT, TINYGLTF_TYPE_SCALAR,
                             1, kElements, false);
  } else {
    out.indices = b.accessor(p.indices, TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT, TINYGLTF_TYPE_SCALAR,
                             1, kElements, false);
  }
  gltf::export_primitive_deformation(b, p, field, out);
  return out;
}

// One sampler + channel animating `node`'s `path` with `values` at the times of accessor `input`.
template <typename T>
void channel(GlbBuilder& b, tinygltf::Animation& animation, int input, int node, const char* path,
             const std::vector<T>& values, int type, size_t components) {
  tinygltf::AnimationSampler sampler;
  sampler.input = input;
  sampler.output = b.accessor(values, kFloat, type, components, 0, false);
  sampler.interpolation = "LINEAR";
  animation.samplers.push_back(sampler);
  tinygltf::AnimationChannel c;
  c.sampler = static_cast<int>(animation.samplers.size() - 1);
  c.target_node = node;
  c.target_path = path;
  animation.channels.push_back(c);
}

template <typename Key>
int time_accessor(GlbBuilder& b, const std::vector<Key>& keys) {
  std::vector<float> times;
  for (const Key& k : keys) times.push_back(k.time);
  return b.accessor(times, kFloat, TINYGLTF_TYPE_SCALAR, 1, 0, true);
}

// T/R/S channels of `node` from a track's keys.
void trs_channels(GlbBuilder& b, tinygltf::Animation& animation, int node, const std::vector<TransformKey>& keys) {
  const int input = time_accessor(b, keys);
  std::vector<glm::vec3> translation, scale;
  std::vector<glm::vec4> rotation;
  for (const TransformKey& k : keys) {
    translation.push_back(k.translation);
    rotation.emplace_back(k.rotation.x, k.rotation.y, k.rotation.z, k.rotation.w);
    scale.push_back(k.scale);
  }
  channel(b, animation, input, node, "translation", translation, TINYGLTF_TYPE_VEC3, 3);
  channel(b, animation, input, node, "rotation", rotation, TINYGLTF_TYPE_VEC4, 4);
  channel(b, animation, input, node, "scale", scale, TINYGLTF_TYPE_VEC3, 3);
}

// The nodes export_glb gives lights and skin joints.
struct NodeMap {
  std::vector<int> lights;               // per light
  std::vector<std::vector<int>> joints;  // per skin, per joint
};

void add_animation(GlbBuilder& b, const Scene& s, int camera_node, const NodeMap& nodes) {
  tinygltf::Animation animation;
  animation.name = "default";
  for (const InstanceTrack& track : s.animation.tracks)
    if (!track.keys.empty()) trs_channels(b, animation, static_cast<int>(track.instance), track.keys);
  for (const LightTrack& track : s.animation.light_tracks)
    if (!track.keys.empty()) trs_channels(b, animation, nodes.lights[track.light], track.keys);
  for (const JointTrack& track : s.animation.joint_tracks)
    if (!track.keys.empty()) trs_channels(b, animation, nodes.joints[track.skin][track.joint], track.keys);
  // Morph weights: one "weights" channel per track on the instance's node, the keys' weights in
  // order (glTF 2.0 3.11: per key, one weight per target).
  for (const MorphTrack& track : s.animation.morph_tracks) {
    if (track.keys.empty()) continue;
    std::vector<float> weights;
    for (const MorphKey& k : track.keys) weights.insert(weights.end(), k.weights.begin(), k.weights.end());
    channel(b, animation, time_accessor(b, track.keys), static_cast<int>(track.instance), "weights", weights,
            TINYGLTF_TYPE_SCALAR, 1);
  }
  if (!s.animation.camera.empty()) {
    const int input = time_accessor(b, s.animation.camera);
    std::vector<glm::vec3> position;
    std::vector<glm::vec4> orientation;
    for (const CameraKey& k : s.animation.camera) {
      position.push_back(k.position);
      orientation.emplace_back(k.orientation.x, k.orientation.y, k.orientation.z, k.orientation.w);
    }
    channel(b, animation, input, camera_node, "translation", position, TINYGLTF_TYPE_VEC3, 3);
    channel(b, animation, input, camera_node, "rotation", orientation, TINYGLTF_TYPE_VEC4, 4);
  }
  if (!animation.channels.empty()) b.model().animations.push_back(std::move(animation));
}

// Which of `count` targets (instances or lights) have a track with keys; `target` names a track's.
template <class Track, class Target>
std::vector<bool> animated_targets(const std::vector<Track>& tracks, size_t count, Target target) {
  std::vector<bool> animated(count, false);
  for (const Track& track : tracks)
    if (target(track) < count && !track.keys.empty()) animated[target(track)] = true;
  return animated;
}

NodeMap add_nodes(GlbBuilder& b, const Scene& s) {
  tinygltf::Model& m = b.model();
  const std::vector<bool> animated =
      animated_targets(s.animation.tracks, s.instances.size(), [](const InstanceTrack& t) { return size_t(t.instance); });
  tinygltf::Scene scene;
  scene.name = s.name;
  scene.extras = gltf::scene_extras(s, s.environment.map ? gltf::export_environment_map(m, *s.environment.map) : tinygltf::Value());
  for (size_t i = 0; i < s.instances.size(); ++i) {
    const Instance& instance = s.instances[i];
    tinygltf::Node node;
    node.name = instance.name;
    node.mesh = static_cast<int>(instance.lod_meshes[0]);
    set_rest_transform(node, instance.transform, animated[i]);
    node.extras = gltf::node_extras(instance, animated[i]);
    node.skin = instance.skin;
    node.weights.assign(instance.morph_weights.begin(), instance.morph_weights.end());
    m.nodes.push_back(node);
    scene.nodes.push_back(static_cast<int>(i));
  }
  tinygltf::Node camera;
  camera.name = "camera";
  camera.camera = 0;
  camera.translation = doubles({s.camera.position.x, s.camera.position.y, s.camera.position.z});
  const glm::quat& q = s.camera.orientation;
  camera.rotation = doubles({q.x, q.y, q.z, q.w});
  m.nodes.push_back(camera);
  scene.nodes.push_back(static_cast<int>(m.nodes.size() - 1));
  tinygltf::Camera lens;
  lens.type = "perspective";
  lens.perspective.yfov = s.camera.yfov;
  lens.perspective.znear = 0.001;
  lens.perspective.zfar = 1e9;
  m.cameras.push_back(lens);

  for (size_t i = 0; i < s.instances.size(); ++i) {
    const Instance& instance = s.instances[i];
    if (instance.lod_meshes.size() < 2) continue;
    tinygltf::Value::Array ids;
    for (size_t l = 1; l < instance.lod_meshes.size(); ++l) {
      tinygltf::Node level;
      level.name = instance.name + "_lod" + std::to_string(l);
      level.mesh = static_cast<int>(instance.lod_meshes[l]);
      m.nodes.push_back(level);
      ids.emplace_back(static_cast<int>(m.nodes.size() - 1));
    }
    m.nodes[i].extensions[kLodExtension] =
        tinygltf::Value(tinygltf::Value::Object{{"ids", tinygltf::Value(ids)}});
    b.use_extension(kLodExtension);
  }
  NodeMap nodes;
  const std::vector<bool> animated_lights =
      animated_targets(s.animation.light_tracks, s.lights.size(), [](const LightTrack& t) { return size_t(t.light); });
  for (size_t i = 0; i < s.lights.size(); ++i) {
    const Light& light = s.lights[i];
    tinygltf::Light out;
    out.name = light.name;
    out.type = light.type == LightType::kPoint ? "point" : light.type == LightType::kSpot ? "spot" : "directional";
    out.color = doubles({light.color.r, light.color.g, light.color.b});
    out.intensity = light.intensity;
    out.range = light.range;
    if (light.type == LightType::kSpot) {
      out.spot.innerConeAngle = light.inner_cone;
      out.spot.outerConeAngle = light.outer_cone;
    }
    m.lights.push_back(out);  // tinygltf writes them as KHR_lights_punctual and lists the extension
    tinygltf::Node node;
    node.name = light.name;
    set_rest_transform(node, light.transform, animated_lights[i]);
    if (animated_lights[i]) node.extras = gltf::rest_matrix_extras(light.transform);
    node.extensions["KHR_lights_punctual"] =
        tinygltf::Value(tinygltf::Value::Object{{"light", tinygltf::Value(static_cast<int>(i))}});
    m.nodes.push_back(node);
    scene.nodes.push_back(static_cast<int>(m.nodes.size() - 1));
    nodes.lights.push_back(static_cast<int>(m.nodes.size() - 1));
  }
  nodes.joints = gltf::export_skins(b, s, scene.nodes);
  m.scenes.push_back(scene);
  m.defaultScene = 0;
  return nodes;
}

}  // namespace

namespace gltf {

void set_rest_transform(tinygltf::Node& node, const glm::mat4& transform, bool animated) {
  if (animated) {
    const TransformKey trs = decompose_trs(transform);
    node.translation = doubles({trs.translation.x, trs.translation.y, trs.translation.z});
    node.rotation = doubles({trs.rotation.x, trs.rotation.y, trs.rotation.z, trs.rotation.w});
    node.scale = doubles({trs.scale.x, trs.scale.y, trs.scale.z});
    return;
  }
  for (int c = 0; c < 4; ++c) {
    for (int r = 0; r < 4; ++r) node.matrix.push_back(transform[c][r]);
  }
}

}  // namespace gltf

std::vector<uint8_t> export_glb(const Scene& scene) {
  try {
    scene.validate();  // indices in range and numbers finite: the writer relies on both
  } catch (const SceneError& e) {
    throw SceneError("cannot export scene '" + scene.name + "': " + e.what());
  }
  GlbBuilder b;
  gltf::export_textures(b.model(), scene.textures);
  for (const Material& m : scene.materials) add_material(b, m);
  for (const Mesh& mesh : scene.meshes) {
    tinygltf::Mesh out;
    out.name = mesh.name;
    const std::string field = "meshes[" + std::to_string(b.model().meshes.size()) + "].primitives[";
    for (size_t p = 0; p < mesh.primitives.size(); ++p)
      out.primitives.push_back(primitive(b, mesh.primitives[p], field + std::to_string(p) + "]"));
    out.weights.assign(mesh.weights.begin(), mesh.weights.end());
    b.model().meshes.push_back(out);
  }
  const NodeMap nodes = add_nodes(b, scene);
  add_animation(b, scene, static_cast<int>(scene.instances.size()), nodes);
  std::ostringstream stream;
  tinygltf::TinyGLTF writer;
  if (!writer.WriteGltfSceneToStream(&b.model(), stream, false, true)) {
    throw SceneError("scene '" + scene.name + "': tinygltf could not write the .glb");
  }
  const std::string bytes = stream.str();
  return {bytes.begin(), bytes.end()};
}

void export_glb_file(const Scene& scene, const std::filesystem::path& path) {
  const std::vector<uint8_t> bytes = export_glb(scene);
  std::ofstream out(path, std::ios::binary | std::ios::trunc);
  if (!out ||
      !out.write(reinterpret_cast<const char*>(bytes.data()),
                 static_cast<std::streamsize>(bytes.size())) ||
      !out.flush()) {
    throw SceneError(path.string() + ": cannot write the .glb");
  }
}

}  // namespace strata::scene
