// characters: deforming meshes in a lit room, for the tests, the benchmarks and the eval of skinned
// and morphing geometry (docs/ARCHITECTURE.md, "Deforming meshes").
// The room: the Cornell box's walls and its ceiling light (2 m box, x in [-1, 1], y in [0, 2],
// z in [-1, 1], open towards +z), with a metal flag pole.
// A flag (skinned): a 1.0 m x 0.6 m double-sided cloth of 16 x 8 quads on a pole, bound to a chain
// of 5 joints 0.25 m apart along its width; every joint past the first turns about the pole's axis
// by 0.35 sin(2 pi 0.8 t - 0.9 k) rad, so a wave runs along the cloth. Each vertex follows the two
// joints it lies between, weighted linearly (at a joint, that joint alone).
// A blob (morph targets): a sphere of radius 0.25 m with two targets, "breathe" (a radial growth
// by 30%, normals unchanged) and "squash" (x and z by 1.2, y by 0.7, with the normals that
// scaling gives), weighted 0.5 + 0.5 sin(2 pi 0.5 t) and 0.5 + 0.5 sin(2 pi 0.5 t + 1.3).
// The camera dollies slowly towards the box over the 120 frames.
#include <cmath>

#include <glm/gtc/matrix_transform.hpp>

#include "scene/builtin/builtins.h"
#include "scene/builtin/common.h"
#include "scene/builtin/shapes.h"
#include "scene/transform.h"

namespace strata::scene::builtin {
namespace {

constexpr uint32_t kFlagJoints = 5;
constexpr float kJointSpacing = 0.25f;
const glm::vec3 kFlagOrigin{-0.55f, 1.35f, -0.25f};  // the first joint, on the pole

// Joint k of the flag at time t, joint to world: the chain of turns about +Y.
std::vector<glm::mat4> flag_joints(float t) {
  std::vector<glm::mat4> joints;
  glm::mat4 m = glm::translate(glm::mat4(1.0f), kFlagOrigin);
  for (uint32_t k = 0; k < kFlagJoints; ++k) {
    if (k > 0) {
      m = glm::translate(m, {kJointSpacing, 0.0f, 0.0f});
      const float angle = 0.35f * std::sin(2.0f * kPi * 0.8f * t - 0.9f * float(k));
      m = glm::rotate(m, angle, {0.0f, 1.0f, 0.0f});
    }
    joints.push_back(m);
  }
  return joints;
}

Primitive flag_cloth(uint32_t material) {
  const float width = kJointSpacing * float(kFlagJoints - 1);
  Primitive p = quad(kFlagOrigin + glm::vec3(0.0f, -0.3f, 0.0f), {width, 0.0f, 0.0f}, {0.0f, 0.6f, 0.0f}, material, 16);
  for (const glm::vec3& x : p.positions) {
    const float s = glm::clamp((x.x - kFlagOrigin.x) / kJointSpacing, 0.0f, float(kFlagJoints - 1));
    const uint32_t k = std::min(uint32_t(s), kFlagJoints - 2);
    const float f = s - float(k);
    p.joints.emplace_back(k, k + 1, 0, 0);
    p.weights.emplace_back(1.0f - f, f, 0.0f, 0.0f);
  }
  return p;
}

Primitive blob(uint32_t material) {
  Primitive p = uv_sphere(0.25f, 32, 16, material);
  MorphTarget breathe;
  MorphTarget squash;
  const glm::vec3 scale(1.2f, 0.7f, 1.2f);
  for (size_t v = 0; v < p.positions.size(); ++v) {
    breathe.positions.push_back(0.3f * p.positions[v]);
    squash.positions.push_back(p.positions[v] * scale - p.positions[v]);
    squash.normals.push_back(glm::normalize(p.normals[v] / scale) - p.normals[v]);
  }
  p.targets = {std::move(breathe), std::move(squash)};
  return p;
}

std::vector<float> blob_weights(float t) {
  const float phase = 2.0f * kPi * 0.5f * t;
  return {0.5f + 0.5f * std::sin(phase), 0.5f + 0.5f * std::sin(phase + 1.3f)};
}

}  // namespace

Scene make_characters() {
  SceneBuilder b("characters");
  const uint32_t white = b.matte("white", {0.73f, 0.73f, 0.73f});
  const uint32_t red = b.matte("red", {0.63f, 0.065f, 0.05f});
  const uint32_t green = b.matte("green", {0.14f, 0.45f, 0.091f});
  const uint32_t light = b.emitter("light", {17.0f, 12.0f, 4.0f});
  const uint32_t cloth = b.matte("cloth", {0.2f, 0.3f, 0.75f});
  b.scene().materials[cloth].double_sided = true;
  const uint32_t pole = b.material("pole", {0.8f, 0.8f, 0.8f}, 1.0f, 0.3f);
  const uint32_t glossy = b.material("blob", {0.9f, 0.55f, 0.2f}, 0.0f, 0.35f);

  b.instance("room", b.mesh("room", cornell_walls(white, red, green)));
  const glm::vec3 up(0.0f, 1.0f, 0.0f);
  b.instance("light", b.mesh("light", {facing_quad({0.0f, 1.99f, 0.0f}, -up, 0.47f, 0.38f, light)}));
  b.instance("pole", b.mesh("pole", {cylinder(0.02f, 1.7f, 16, pole)}),
             glm::translate(glm::mat4(1.0f), {kFlagOrigin.x - 0.02f, 0.0f, kFlagOrigin.z}));

  // The flag: its vertices are where the bind pose (the joints at t = 0 with every turn 0) has
  // them, its instance at the identity, so inverse bind matrices are the bind pose's inverses.
  Skin skin;
  skin.name = "flag";
  for (uint32_t k = 0; k < kFlagJoints; ++k)
    skin.inverse_bind.push_back(glm::inverse(glm::translate(glm::mat4(1.0f), kFlagOrigin + glm::vec3(kJointSpacing * float(k), 0, 0))));
  skin.joints = flag_joints(0.0f);
  Scene& s = b.scene();
  s.skins.push_back(std::move(skin));
  const uint32_t flag = b.instance("flag", b.mesh("flag", {flag_cloth(cloth)}));
  s.instances[flag].skin = 0;
  for (uint32_t k = 0; k < kFlagJoints; ++k) {
    JointTrack track{0, k, {}};
    for (uint32_t f = 0; f < kFrameCount; ++f) {
      TransformKey key = decompose_trs(flag_joints(key_time(f))[k]);
      key.time = key_time(f);
      track.keys.push_back(key);
    }
    s.animation.joint_tracks.push_back(std::move(track));
  }

  const uint32_t blob_mesh = b.mesh("blob", {blob(glossy)});
  s.meshes[blob_mesh].weights = {0.0f, 0.0f};
  const uint32_t blob_instance = b.instance("blob", blob_mesh, glm::translate(glm::mat4(1.0f), {0.45f, 0.3f, 0.25f}));
  s.instances[blob_instance].morph_weights = blob_weights(0.0f);
  MorphTrack morph{blob_instance, {}};
  for (uint32_t f = 0; f < kFrameCount; ++f) morph.keys.push_back({key_time(f), blob_weights(key_time(f))});
  s.animation.morph_tracks.push_back(std::move(morph));

  b.camera_path([](uint32_t f) {
    const float t = float(f) / float(kFrameCount - 1);
    return std::pair{glm::vec3(0.15f * t, 1.0f, 3.8f - 0.5f * t), glm::vec3(0.0f, 0.95f, 0.0f)};
  });
  b.scene().camera.yfov = 0.69f;
  return b.finish();
}

}  // namespace strata::scene::builtin
