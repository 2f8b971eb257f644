// glTF animations (glTF 2.0 3.11) to the default Animation. All animations of the file play
// together from t = 0 (when two channels drive the same node property, the first one wins).
// Translation, rotation, scale and weights channels with LINEAR or STEP samplers are used
// (CUBICSPLINE is rejected). A channel on a node moves every instance, light and skin joint under
// it: each affected instance, light, joint (and the camera) is keyed at the union of its channels'
// key times with its composed world transform, decomposed into T/R/S. STEP channels get an extra
// key just before each jump, so linear interpolation between keys reproduces the step. A node
// whose ancestors all rest at the identity, unanimated (a root node, or a joint under export_glb's
// skeleton node), has its own channels copied without composing, so keys written by export_glb
// come back bit for bit. A weights channel becomes the MorphTrack of its node's instance, its
// keys as the file has them.
#include <algorithm>
#include <cmath>
#include <limits>
#include <map>

#include "scene/animation.h"
#include "scene/gltf_accessor.h"
#include "scene/gltf_convert.h"
#include "scene/transform.h"

namespace strata::scene::gltf {
namespace {

// Bounds the keys a file can make us generate (instances, lights and joints x union of key times,
// plus morph keys x targets).
constexpr size_t kMaxAnimationKeys = 4'000'000;

enum class Path { kTranslation, kRotation, kScale };

struct Channel {
  bool step = false;
  std::vector<float> times;
  std::vector<glm::vec4> values;  // xyz (w unused), or rotation as (x, y, z, w)
};

using ChannelMap = std::map<std::pair<int, Path>, Channel>;

// A weights channel: per key, one weight per morph target of the node's mesh.
struct MorphChannel {
  bool step = false;
  std::vector<float> times;
  std::vector<float> values;  // times.size() x targets
  size_t targets = 0;
};

using MorphChannelMap = std::map<int, MorphChannel>;

// The sampler's interpolation (true: STEP) and its key times, checked.
bool read_times(const Source& s, const tinygltf::AnimationSampler& sampler, const std::string& field,
                std::vector<float>& times) {
  const bool step = sampler.interpolation == "STEP";
  if (!step && sampler.interpolation != "LINEAR") {
    s.fail(field + ".interpolation",
           "= " + sampler.interpolation + " is not supported (LINEAR or STEP)");
  }
  times = read_floats(s, sampler.input, 1, Components::kFloatOnly, field + ".input");
  for (size_t k = 1; k < times.size(); ++k) {
    if (times[k] < times[k - 1])
      s.fail(field + ".input", "is not sorted by time (key " + std::to_string(k) + ")");
  }
  return step;
}

Channel read_channel(const Source& s, size_t a, const tinygltf::AnimationSampler& sampler,
                     int sampler_index, Path path) {
  const std::string field =
      at(at("animations", a) + ".samplers", static_cast<size_t>(sampler_index));
  Channel c;
  c.step = read_times(s, sampler, field, c.times);
  const int width = path == Path::kRotation ? 4 : 3;
  const std::vector<float> v =
      read_floats(s, sampler.output, width,
                  path == Path::kRotation ? Components::kFloatOrNormalized : Components::kFloatOnly,
                  field + ".output");
  if (v.size() / static_cast<size_t>(width) != c.times.size()) {
    s.fail(field + ".output", "has " + std::to_string(v.size() / static_cast<size_t>(width)) +
                                  " elements, input has " + std::to_string(c.times.size()));
  }
  for (size_t k = 0; k < c.times.size(); ++k) {
    const float* e = &v[k * static_cast<size_t>(width)];
    if (path == Path::kRotation) {
      const glm::quat q = read_rotation(s, e[0], e[1], e[2], e[3], field + ".output");
      c.values.emplace_back(q.x, q.y, q.z, q.w);
    } else {
      c.values.emplace_back(e[0], e[1], e[2], 0.0f);
    }
  }
  return c;
}

// 3.11: a weights channel's output holds, per key, one weight per morph target of the node's mesh.
MorphChannel read_morph_channel(const Source& s, const Scene& scene, size_t a,
                                const tinygltf::Animation& animation, size_t c) {
  const tinygltf::AnimationChannel& channel = animation.channels[c];
  const std::string channel_field = at(at("animations", a) + ".channels", c);
  const tinygltf::Node& node = s.model.nodes[static_cast<size_t>(channel.target_node)];
  const std::string node_field = at("nodes", static_cast<size_t>(channel.target_node));
  if (node.mesh != -1) s.check_index(node_field + ".mesh", node.mesh, scene.meshes.size(), "meshes");
  MorphChannel out;
  out.targets = node.mesh >= 0 ? scene.meshes[static_cast<size_t>(node.mesh)].weights.size() : 0;
  if (out.targets == 0)
    s.fail(channel_field + ".target.path", "= weights, but " + node_field + " has no mesh with morph targets");
  const std::string field = at(at("animations", a) + ".samplers", static_cast<size_t>(channel.sampler));
  const tinygltf::AnimationSampler& sampler = animation.samplers[static_cast<size_t>(channel.sampler)];
  out.step = read_times(s, sampler, field, out.times);
  out.values = read_floats(s, sampler.output, 1, Components::kFloatOrNormalized, field + ".output");
  if (out.values.size() != out.times.size() * out.targets) {
    s.fail(field + ".output", "has " + std::to_string(out.values.size()) + " elements, not input's " +
                                  std::to_string(out.times.size()) + " keys x " + std::to_string(out.targets) +
                                  " morph targets of " + node_field + "'s mesh");
  }
  return out;
}

void read_channels(const Source& s, const Scene& scene, ChannelMap& channels, MorphChannelMap& morphs) {
  for (size_t a = 0; a < s.model.animations.size(); ++a) {
    const tinygltf::Animation& animation = s.model.animations[a];
    for (size_t c = 0; c < animation.channels.size(); ++c) {
      const tinygltf::AnimationChannel& channel = animation.channels[c];
      const std::string field = at(at("animations", a) + ".channels", c);
      Path path = Path::kTranslation;
      if (channel.target_path == "translation")
        path = Path::kTranslation;
      else if (channel.target_path == "rotation")
        path = Path::kRotation;
      else if (channel.target_path == "scale")
        path = Path::kScale;
      else if (channel.target_path != "weights")
        continue;  // e.g. KHR_animation_pointer's "pointer": the extension is listed as ignored
      s.check_index(field + ".target.node", channel.target_node, s.model.nodes.size(), "nodes");
      s.check_index(field + ".sampler", channel.sampler, animation.samplers.size(), "samplers");
      if (channel.target_path == "weights") {
        if (morphs.count(channel.target_node) != 0) continue;
        MorphChannel read = read_morph_channel(s, scene, a, animation, c);
        if (!read.times.empty()) morphs.emplace(channel.target_node, std::move(read));
        continue;
      }
      const auto key = std::make_pair(channel.target_node, path);
      if (channels.count(key) != 0) continue;
      Channel read = read_channel(s, a, animation.samplers[static_cast<size_t>(channel.sampler)],
                                  channel.sampler, path);
      if (!read.times.empty()) channels.emplace(key, std::move(read));
    }
  }
}

// A weights channel's keys. LINEAR: the file's keys as they are. STEP: each key is held until the
// next, by an extra key just before each jump.
std::vector<MorphKey> morph_keys(const MorphChannel& c) {
  std::vector<MorphKey> keys;
  auto weights = [&](size_t k) {
    return std::vector<float>(c.values.begin() + std::ptrdiff_t(k * c.targets),
                              c.values.begin() + std::ptrdiff_t((k + 1) * c.targets));
  };
  for (size_t k = 0; k < c.times.size(); ++k) {
    if (c.step && k > 0 && c.times[k] > c.times[k - 1]) {
      const float before = std::nextafter(c.times[k], -std::numeric_limits<float>::infinity());
      keys.push_back(MorphKey{before, weights(k - 1)});
    }
    keys.push_back(MorphKey{c.times[k], weights(k)});
  }
  return keys;
}

glm::vec4 sample(const Channel& c, Path path, float t) {
  if (t <= c.times.front()) return c.values.front();
  if (t >= c.times.back()) return c.values.back();
  const size_t k =
      static_cast<size_t>(std::upper_bound(c.times.begin(), c.times.end(), t) - c.times.begin()) -
      1;
  if (c.step || t == c.times[k]) return c.values[k];
  const float w = (t - c.times[k]) / (c.times[k + 1] - c.times[k]);
  if (path != Path::kRotation) return glm::mix(c.values[k], c.values[k + 1], w);
  const glm::vec4 a = c.values[k], b = c.values[k + 1];
  const glm::quat q =
      glm::normalize(glm::slerp(glm::quat(a.w, a.x, a.y, a.z), glm::quat(b.w, b.x, b.y, b.z), w));
  return {q.x, q.y, q.z, q.w};
}

// Node `node` from its root down, and whether any of them is animated.
std::vector<int> chain_of(const NodeTree& tree, int node) {
  std::vector<int> chain;
  for (int n = node; n >= 0; n = tree.parent[static_cast<size_t>(n)]) chain.push_back(n);
  std::reverse(chain.begin(), chain.end());
  return chain;
}

TransformKey local_at(const NodeTree& tree, const ChannelMap& channels, int node, float t) {
  TransformKey trs = tree.local_trs[static_cast<size_t>(node)];
  if (auto it = channels.find({node, Path::kTranslation}); it != channels.end()) {
    trs.translation = glm::vec3(sample(it->second, Path::kTranslation, t));
  }
  if (auto it = channels.find({node, Path::kRotation}); it != channels.end()) {
    const glm::vec4 q = sample(it->second, Path::kRotation, t);
    trs.rotation = glm::quat(q.w, q.x, q.y, q.z);
  }
  if (auto it = channels.find({node, Path::kScale}); it != channels.end()) {
    trs.scale = glm::vec3(sample(it->second, Path::kScale, t));
  }
  return trs;
}

// The key times of every channel on `chain`; empty when nothing on it is animated.
std::vector<float> key_times(const ChannelMap& channels, const std::vector<int>& chain) {
  std::vector<float> times;
  for (int node : chain) {
    for (Path path : {Path::kTranslation, Path::kRotation, Path::kScale}) {
      const auto it = channels.find({node, path});
      if (it == channels.end()) continue;
      const Channel& c = it->second;
      times.insert(times.end(), c.times.begin(), c.times.end());
      if (!c.step) continue;
      for (size_t k = 1; k < c.times.size(); ++k) {
        times.push_back(std::nextafter(c.times[k], -std::numeric_limits<float>::infinity()));
      }
    }
  }
  std::sort(times.begin(), times.end());
  times.erase(std::unique(times.begin(), times.end()), times.end());
  return times;
}

bool animated(const ChannelMap& channels, int node) {
  return channels.count({node, Path::kTranslation}) + channels.count({node, Path::kRotation}) +
             channels.count({node, Path::kScale}) >
         0;
}

// The world TRS of the chain's last node at time t. Ancestors at rest at the identity change
// nothing and are left out; when no other remains, the node's own TRS is the key, exactly.
TransformKey world_at(const NodeTree& tree, const ChannelMap& channels,
                      const std::vector<int>& chain, float t) {
  std::vector<int> moving;
  for (size_t k = 0; k + 1 < chain.size(); ++k) {
    const int node = chain[k];
    if (animated(channels, node) || tree.local_matrix[static_cast<size_t>(node)] != glm::mat4(1.0f))
      moving.push_back(node);
  }
  if (moving.empty()) {
    TransformKey key = local_at(tree, channels, chain.back(), t);
    key.time = t;
    return key;
  }
  moving.push_back(chain.back());
  glm::mat4 world(1.0f);
  for (int node : moving) {
    world = world * (animated(channels, node) ? compose_trs(local_at(tree, channels, node, t))
                                              : tree.local_matrix[static_cast<size_t>(node)]);
  }
  TransformKey key = decompose_trs(world);
  key.time = t;
  return key;
}

}  // namespace

void convert_animations(const Source& s, const NodeTree& tree, Scene& scene) {
  ChannelMap channels;
  MorphChannelMap morphs;
  read_channels(s, scene, channels, morphs);
  if (channels.empty() && morphs.empty()) return;
  size_t total_keys = 0;
  auto count_keys = [&](size_t keys) {
    total_keys += keys;
    if (total_keys > kMaxAnimationKeys) {
      s.fail("animations",
             "expand to more than " + std::to_string(kMaxAnimationKeys) + " keys (transform keys and morph weights)");
    }
  };
  for (size_t i = 0; i < scene.instances.size(); ++i) {
    const auto it = morphs.find(static_cast<int>(tree.instance_node[i]));
    if (it == morphs.end()) continue;
    MorphTrack track{static_cast<uint32_t>(i), morph_keys(it->second)};
    count_keys(track.keys.size() * it->second.targets);
    scene.animation.morph_tracks.push_back(std::move(track));
  }
  for (size_t k = 0; k < s.model.skins.size(); ++k) {
    const std::vector<int>& joints = s.model.skins[k].joints;
    for (size_t j = 0; j < joints.size(); ++j) {
      const std::vector<int> chain = chain_of(tree, joints[j]);
      const std::vector<float> times = key_times(channels, chain);
      if (times.empty()) continue;
      count_keys(times.size());
      JointTrack track{static_cast<uint32_t>(k), static_cast<uint32_t>(j), {}};
      for (float t : times) track.keys.push_back(world_at(tree, channels, chain, t));
      scene.animation.joint_tracks.push_back(std::move(track));
    }
  }
  for (size_t i = 0; i < scene.instances.size(); ++i) {
    const std::vector<int> chain = chain_of(tree, static_cast<int>(tree.instance_node[i]));
    const std::vector<float> times = key_times(channels, chain);
    if (times.empty()) continue;
    count_keys(times.size());
    InstanceTrack track{static_cast<uint32_t>(i), {}};
    for (float t : times) track.keys.push_back(world_at(tree, channels, chain, t));
    scene.animation.tracks.push_back(std::move(track));
  }
  for (size_t i = 0; i < scene.lights.size(); ++i) {
    const std::vector<int> chain = chain_of(tree, static_cast<int>(tree.light_node[i]));
    const std::vector<float> times = key_times(channels, chain);
    if (times.empty()) continue;
    count_keys(times.size());
    LightTrack track{static_cast<uint32_t>(i), {}};
    for (float t : times) track.keys.push_back(world_at(tree, channels, chain, t));
    scene.animation.light_tracks.push_back(std::move(track));
  }
  if (tree.camera_node >= 0) {
    const std::vector<int> chain = chain_of(tree, tree.camera_node);
    const std::vector<float> times = key_times(channels, chain);
    count_keys(times.size());
    for (float t : times) {
      const TransformKey key = world_at(tree, channels, chain, t);
      scene.animation.camera.push_back(CameraKey{t, key.translation, key.rotation});
    }
  }
}

}  // namespace strata::scene::gltf
