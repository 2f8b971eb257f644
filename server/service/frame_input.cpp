#include "service/frame_input.h"

#include <cmath>
#include <set>
#include <string>

#include "service/errors.h"
#include "service/input_checks.h"
#include "service/options.h"

namespace strata::service {
namespace {

std::string instance_range(const scene::Scene& s) {
  return "scene '" + s.name + "' has " + std::to_string(s.instances.size()) + " instances (ids 0.." +
         std::to_string(s.instances.size() - 1) + ")";
}

void check_instance(uint32_t id, const scene::Scene& s, const std::string& field) {
  if (id >= s.instances.size()) fail_invalid(field + " = " + std::to_string(id) + " is not an instance id: " + instance_range(s));
}

}  // namespace

void PendingInput::merge_newer(PendingInput&& newer) {
  const uint64_t merged = coalesced + 1 + newer.coalesced;
  if (newer.animation_frame) {
    // The newer input restarts from the animation: earlier scene-state changes are superseded.
    animation_frame = newer.animation_frame;
    camera.reset();
    transforms.clear();
    lods.clear();
    lights.clear();
    joints.clear();
    morph_weights.clear();
  }
  if (newer.camera) camera = newer.camera;
  for (auto& [id, m] : newer.transforms) transforms[id] = m;
  for (auto& [id, level] : newer.lods) lods[id] = level;
  for (auto& [id, m] : newer.lights) lights[id] = m;
  for (auto& [id, pose] : newer.joints)
    for (auto& [j, m] : pose) joints[id][j] = m;
  for (auto& [id, w] : newer.morph_weights) morph_weights[id] = std::move(w);
  options.MergeFrom(newer.options);
  if (newer.resolution) resolution = newer.resolution;
  if (!newer.encodings.empty()) encodings = std::move(newer.encodings);
  sequence = newer.sequence;
  received = newer.received;
  coalesced = merged;
}

PendingInput parse_frame_input(const v1::FrameInput& in, const scene::Scene& scene, const ServiceLimits& limits) {
  PendingInput p;
  p.sequence = in.sequence();
  p.received = std::chrono::steady_clock::now();
  if (in.has_animation_frame()) p.animation_frame = in.animation_frame();
  if (in.has_camera()) p.camera = check_camera(in.camera(), "camera");

  std::set<uint32_t> seen;
  for (int i = 0; i < in.transforms_size(); ++i) {
    const auto& t = in.transforms(i);
    const std::string field = "transforms[" + std::to_string(i) + "]";
    check_instance(t.instance_id(), scene, field + ".instance_id");
    if (!seen.insert(t.instance_id()).second)
      fail_invalid(field + ".instance_id = " + std::to_string(t.instance_id()) + " appears more than once in transforms");
    p.transforms[t.instance_id()] = check_transform(t, field);
  }
  seen.clear();
  for (int i = 0; i < in.light_transforms_size(); ++i) {
    const auto& t = in.light_transforms(i);
    const std::string field = "light_transforms[" + std::to_string(i) + "]";
    if (t.light_id() >= scene.lights.size())
      fail_invalid(field + ".light_id = " + std::to_string(t.light_id()) + " is not a light id: scene '" + scene.name + "' has " +
                   std::to_string(scene.lights.size()) + " punctual light(s)");
    if (!seen.insert(t.light_id()).second)
      fail_invalid(field + ".light_id = " + std::to_string(t.light_id()) + " appears more than once in light_transforms");
    p.lights[t.light_id()] = check_light_transform(t, field);
  }
  seen.clear();
  for (int i = 0; i < in.joint_poses_size(); ++i) {
    const auto& pose = in.joint_poses(i);
    const std::string field = "joint_poses[" + std::to_string(i) + "]";
    check_instance(pose.instance_id(), scene, field + ".instance_id");
    if (!seen.insert(pose.instance_id()).second)
      fail_invalid(field + ".instance_id = " + std::to_string(pose.instance_id()) + " appears more than once in joint_poses");
    const auto& inst = scene.instances[pose.instance_id()];
    if (inst.skin < 0)
      fail_invalid(field + ".instance_id = " + std::to_string(pose.instance_id()) + " '" + inst.name + "' is not skinned (SceneAnalysis: joints = 0)");
    const size_t count = scene.skins[size_t(inst.skin)].joints.size();
    auto& joints = p.joints[pose.instance_id()];
    for (int k = 0; k < pose.joints_size(); ++k) {
      const auto& j = pose.joints(k);
      const std::string jf = field + ".joints[" + std::to_string(k) + "]";
      if (j.joint() >= count)
        fail_invalid(jf + ".joint = " + std::to_string(j.joint()) + " is not a joint of instance " + std::to_string(pose.instance_id()) +
                     " '" + inst.name + "': its skin has " + std::to_string(count) + " joints (0.." + std::to_string(count - 1) + ")");
      if (joints.contains(j.joint())) fail_invalid(jf + ".joint = " + std::to_string(j.joint()) + " appears more than once");
      joints[j.joint()] = check_joint_transform(j, jf);
    }
  }
  seen.clear();
  for (int i = 0; i < in.morph_weights_size(); ++i) {
    const auto& mw = in.morph_weights(i);
    const std::string field = "morph_weights[" + std::to_string(i) + "]";
    check_instance(mw.instance_id(), scene, field + ".instance_id");
    if (!seen.insert(mw.instance_id()).second)
      fail_invalid(field + ".instance_id = " + std::to_string(mw.instance_id()) + " appears more than once in morph_weights");
    const auto& inst = scene.instances[mw.instance_id()];
    const size_t targets = inst.morph_weights.size();
    if (size_t(mw.weights_size()) != targets)
      fail_invalid(field + ".weights has " + std::to_string(mw.weights_size()) + " weights; instance " + std::to_string(mw.instance_id()) +
                   " '" + inst.name + "' has " + std::to_string(targets) + " morph target(s)");
    std::vector<float> w(mw.weights().begin(), mw.weights().end());
    for (size_t k = 0; k < w.size(); ++k)
      if (!std::isfinite(w[k]) || std::fabs(w[k]) > k_max_morph_weight)
        fail_invalid(field + ".weights[" + std::to_string(k) + "] = " + format_float(w[k]) + " is outside [-" +
                     format_float(k_max_morph_weight) + ", " + format_float(k_max_morph_weight) + "]");
    p.morph_weights[mw.instance_id()] = std::move(w);
  }
  seen.clear();
  for (int i = 0; i < in.lod_changes_size(); ++i) {
    const auto& c = in.lod_changes(i);
    const std::string field = "lod_changes[" + std::to_string(i) + "]";
    check_instance(c.instance_id(), scene, field + ".instance_id");
    if (!seen.insert(c.instance_id()).second)
      fail_invalid(field + ".instance_id = " + std::to_string(c.instance_id()) + " appears more than once in lod_changes");
    const auto& inst = scene.instances[c.instance_id()];
    const size_t levels = inst.lod_meshes.size();
    if (c.level() >= levels)
      fail_invalid(field + ".level = " + std::to_string(c.level()) + " is out of range for instance " +
                   std::to_string(c.instance_id()) + " '" + inst.name + "': it has " + std::to_string(levels) +
                   " LoD level(s), 0.." + std::to_string(levels - 1));
    p.lods[c.instance_id()] = c.level();
  }
  if (in.has_options()) {
    check_options(in.options(), limits, "options");
    p.options = in.options();
  }
  if (in.has_resolution()) {
    check_resolution(in.resolution(), limits, "resolution");
    p.resolution = std::make_pair(in.resolution().width(), in.resolution().height());
  }
  if (!in.encodings().empty()) p.encodings = check_encodings(in.encodings(), "encodings");
  return p;
}

}  // namespace strata::service
