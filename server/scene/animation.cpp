#include "scene/animation.h"

#include <algorithm>

#include "scene/transform.h"

namespace strata::scene {
namespace {

// Index i of the segment [keys[i], keys[i+1]] holding `time` and the blend weight within it.
// Returns false (with i = the clamped key) when `time` is outside the keys or exactly on key i.
template <typename Key>
bool find_segment(const std::vector<Key>& keys, float time, size_t& index, float& weight) {
  if (time <= keys.front().time) {
    index = 0;
    return false;
  }
  if (time >= keys.back().time) {
    index = keys.size() - 1;
    return false;
  }
  const auto upper = std::upper_bound(keys.begin(), keys.end(), time,
                                      [](float t, const Key& k) { return t < k.time; });
  index = static_cast<size_t>(upper - keys.begin()) - 1;
  const float t0 = keys[index].time;
  const float t1 = keys[index + 1].time;
  if (time == t0 || t1 <= t0) return false;
  weight = (time - t0) / (t1 - t0);
  return true;
}

// Between two equal keys the value is the key itself, exactly: a(1 - w) + a w is not a in floating
// point, and a still camera or object must stay bit-identical from frame to frame (change tracking
// and HISTORY_CAMERA_STILL compare exactly).
template <class T>
T mix_keys(const T& a, const T& b, float weight) {
  return a == b ? a : glm::mix(a, b, weight);
}

glm::quat slerp_unit(const glm::quat& a, const glm::quat& b, float weight) {
  if (a == b) return a;
  // glm::slerp takes the shorter arc; for nearly equal rotations it falls back to an
  // unnormalised lerp, hence the normalisation.
  return glm::normalize(glm::slerp(a, b, weight));
}

}  // namespace

CameraKey sample_camera(const std::vector<CameraKey>& keys, float time) {
  size_t i = 0;
  float w = 0.0f;
  if (!find_segment(keys, time, i, w)) return keys[i];
  CameraKey out;
  out.time = time;
  out.position = mix_keys(keys[i].position, keys[i + 1].position, w);
  out.orientation = slerp_unit(keys[i].orientation, keys[i + 1].orientation, w);
  return out;
}

TransformKey sample_transform(const std::vector<TransformKey>& keys, float time) {
  size_t i = 0;
  float w = 0.0f;
  if (!find_segment(keys, time, i, w)) return keys[i];
  TransformKey out;
  out.time = time;
  out.translation = mix_keys(keys[i].translation, keys[i + 1].translation, w);
  out.rotation = slerp_unit(keys[i].rotation, keys[i + 1].rotation, w);
  out.scale = mix_keys(keys[i].scale, keys[i + 1].scale, w);
  return out;
}

std::vector<float> sample_morph(const std::vector<MorphKey>& keys, float time) {
  size_t i = 0;
  float w = 0.0f;
  if (!find_segment(keys, time, i, w)) return keys[i].weights;
  std::vector<float> out(keys[i].weights.size());
  for (size_t t = 0; t < out.size(); ++t) out[t] = mix_keys(keys[i].weights[t], keys[i + 1].weights[t], w);
  return out;
}

float frame_time(uint32_t frame, float frames_per_second) {
  return static_cast<float>(static_cast<double>(frame) / static_cast<double>(frames_per_second));
}

float animation_duration(const Animation& animation) {
  float end = 0.0f;
  if (!animation.camera.empty()) end = std::max(end, animation.camera.back().time);
  for (const InstanceTrack& track : animation.tracks) {
    if (!track.keys.empty()) end = std::max(end, track.keys.back().time);
  }
  if (!animation.lod_schedule.empty()) end = std::max(end, animation.lod_schedule.back().time);
  for (const LightTrack& track : animation.light_tracks) {
    if (!track.keys.empty()) end = std::max(end, track.keys.back().time);
  }
  for (const JointTrack& track : animation.joint_tracks) {
    if (!track.keys.empty()) end = std::max(end, track.keys.back().time);
  }
  for (const MorphTrack& track : animation.morph_tracks) {
    if (!track.keys.empty()) end = std::max(end, track.keys.back().time);
  }
  return end;
}

FrameState Scene::frame_state(uint32_t frame) const {
  const float time = frame_time(frame, animation.frames_per_second);
  FrameState state;
  state.camera = camera;
  if (!animation.camera.empty()) {
    const CameraKey key = sample_camera(animation.camera, time);
    state.camera.position = key.position;
    state.camera.orientation = key.orientation;
  }
  state.transforms.reserve(instances.size());
  state.lods.reserve(instances.size());
  for (const Instance& instance : instances) {
    state.transforms.push_back(instance.transform);
    state.lods.push_back(instance.lod);
  }
  for (const InstanceTrack& track : animation.tracks) {
    if (track.instance < instances.size() && !track.keys.empty()) {
      state.transforms[track.instance] = compose_trs(sample_transform(track.keys, time));
    }
  }
  state.lights.reserve(lights.size());
  for (const Light& light : lights) state.lights.push_back(light.transform);
  for (const LightTrack& track : animation.light_tracks) {
    if (track.light < lights.size() && !track.keys.empty())
      state.lights[track.light] = compose_trs(sample_transform(track.keys, time));
  }
  // Every instance of a skin poses its joints alike; a client may pose each one apart.
  std::vector<std::vector<glm::mat4>> skin_joints;
  for (const Skin& skin : skins) skin_joints.push_back(skin.joints);
  for (const JointTrack& track : animation.joint_tracks) {
    if (track.skin < skin_joints.size() && track.joint < skin_joints[track.skin].size() && !track.keys.empty())
      skin_joints[track.skin][track.joint] = compose_trs(sample_transform(track.keys, time));
  }
  state.joints.resize(instances.size());
  state.morph_weights.resize(instances.size());
  for (size_t i = 0; i < instances.size(); ++i) {
    if (instances[i].skin >= 0 && size_t(instances[i].skin) < skin_joints.size()) state.joints[i] = skin_joints[size_t(instances[i].skin)];
    state.morph_weights[i] = instances[i].morph_weights;
  }
  for (const MorphTrack& track : animation.morph_tracks) {
    if (track.instance < instances.size() && !track.keys.empty())
      state.morph_weights[track.instance] = sample_morph(track.keys, time);
  }
  // The schedule is sorted by time, so the last key at or before `time` wins.
  for (const LodKey& key : animation.lod_schedule) {
    if (key.time > time) break;
    if (key.instance < instances.size()) state.lods[key.instance] = key.level;
  }
  return state;
}

}  // namespace strata::scene
