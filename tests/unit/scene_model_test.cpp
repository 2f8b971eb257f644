// Scene model: frame_state sampling, validate() and triangle_count(), TRS helpers.
#include <cmath>
#include <limits>
#include <string>

#include <glm/gtc/matrix_transform.hpp>
#include <gtest/gtest.h>

#include "scene/animation.h"
#include "scene/scene.h"
#include "scene/transform.h"

namespace strata::scene {
namespace {

constexpr float kHalfPi = 1.57079632679f;

Primitive triangle(uint32_t material = 0) {
  Primitive p;
  p.positions = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}};
  p.normals.assign(3, {0, 0, 1});
  p.uvs = {{0, 0}, {1, 0}, {0, 1}};
  p.indices = {0, 1, 2};
  p.material = material;
  return p;
}

// Two meshes, one material, two instances (instance 1 has two LoD levels).
Scene small_scene() {
  Scene s;
  s.name = "small";
  s.materials.push_back(Material{});
  s.meshes.push_back(Mesh{"a", {triangle()}});
  s.meshes.push_back(Mesh{"b", {triangle(), triangle()}});
  s.instances.push_back(Instance{"first", {0}, glm::mat4(1.0f), 0});
  s.instances.push_back(Instance{"second", {1, 0}, glm::translate(glm::mat4(1.0f), {5, 0, 0}), 1});
  return s;
}

void expect_near(const glm::vec3& a, const glm::vec3& b, float eps = 1e-5f) {
  EXPECT_NEAR(a.x, b.x, eps);
  EXPECT_NEAR(a.y, b.y, eps);
  EXPECT_NEAR(a.z, b.z, eps);
}

std::string validate_message(const Scene& s) {
  try {
    s.validate();
  } catch (const SceneError& e) {
    return e.what();
  }
  return "";
}

TEST(SceneFrameState, CameraLerpsPositionAndSlerpsOrientation) {
  Scene s = small_scene();
  s.animation.frames_per_second = 4.0f;
  s.animation.camera = {CameraKey{0.0f, {0, 0, 0}, glm::quat(1, 0, 0, 0)},
                        CameraKey{1.0f, {2, 4, 0}, glm::angleAxis(kHalfPi, glm::vec3(0, 1, 0))}};
  const FrameState state = s.frame_state(2);  // t = 0.5
  expect_near(state.camera.position, {1, 2, 0});
  const glm::quat expected = glm::angleAxis(kHalfPi / 2, glm::vec3(0, 1, 0));
  EXPECT_NEAR(std::abs(glm::dot(state.camera.orientation, expected)), 1.0f, 1e-6f);
  // A quarter of the way: 22.5 degrees about +Y turns -Z into (-sin, 0, -cos) of 22.5 degrees.
  const glm::vec3 forward = s.frame_state(1).camera.orientation * glm::vec3(0, 0, -1);
  expect_near(forward, {-std::sin(kHalfPi / 4), 0, -std::cos(kHalfPi / 4)});
  EXPECT_EQ(state.camera.yfov, s.camera.yfov);  // lens settings are not animated
}

TEST(SceneFrameState, ClampsOutsideKeysAndHitsKeysExactly) {
  Scene s = small_scene();
  s.animation.frames_per_second = 10.0f;
  const CameraKey a{0.5f, {1, 2, 3}, glm::normalize(glm::quat(0.9f, 0.1f, 0.3f, 0.2f))};
  const CameraKey b{1.0f, {-4, 5, 6}, glm::normalize(glm::quat(0.2f, 0.7f, 0.1f, 0.4f))};
  s.animation.camera = {a, b};
  EXPECT_EQ(s.frame_state(0).camera.position, a.position);  // before the first key
  EXPECT_EQ(s.frame_state(5).camera.position, a.position);  // exactly on it
  EXPECT_EQ(s.frame_state(5).camera.orientation, a.orientation);
  EXPECT_EQ(s.frame_state(10).camera.orientation, b.orientation);
  EXPECT_EQ(s.frame_state(500).camera.position, b.position);  // after the last key
}

// Between equal keys (a still camera or object keyed at both ends, as cornell's camera) every frame
// is the key bit for bit: interpolating a with itself is not exact in floating point, and the
// renderer compares frames exactly (change tracking, HISTORY_CAMERA_STILL).
TEST(SceneFrameState, EqualKeysHoldTheirValueExactly) {
  Scene s = small_scene();
  s.animation.frames_per_second = 24.0f;
  const CameraKey a{0.0f, {0.1f, 1.0f, 3.8f}, glm::normalize(glm::quat(0.9f, 0.1f, 0.3f, 0.2f))};
  CameraKey b = a;
  b.time = 5.0f;
  s.animation.camera = {a, b};
  s.animation.tracks.push_back({0, {{0.0f, {0.3f, 0.7f, -1.1f}, glm::normalize(glm::quat(0.8f, 0.2f, 0.1f, 0.3f)), {1.3f, 1.3f, 1.3f}},
                                    {5.0f, {0.3f, 0.7f, -1.1f}, glm::normalize(glm::quat(0.8f, 0.2f, 0.1f, 0.3f)), {1.3f, 1.3f, 1.3f}}}});
  const FrameState first = s.frame_state(0);
  for (uint32_t f = 1; f < 120; ++f) {
    const FrameState state = s.frame_state(f);
    ASSERT_EQ(state.camera, first.camera) << "frame " << f;
    ASSERT_EQ(state.transforms, first.transforms) << "frame " << f;
  }
}

TEST(SceneFrameState, NoCameraKeysKeepsTheSceneCamera) {
  const Scene s = small_scene();
  EXPECT_EQ(s.frame_state(17).camera, s.camera);
}

TEST(SceneFrameState, TrackComposesTranslationRotationScale) {
  Scene s = small_scene();
  s.animation.frames_per_second = 1.0f;
  TransformKey k0;
  k0.time = 0.0f;
  k0.translation = {1, 2, 3};
  k0.rotation = glm::angleAxis(kHalfPi, glm::vec3(0, 0, 1));
  k0.scale = {2, 1, 1};
  TransformKey k1 = k0;
  k1.time = 2.0f;
  k1.translation = {3, 2, 3};
  k1.scale = {4, 1, 1};
  s.animation.tracks.push_back(InstanceTrack{0, {k0, k1}});
  // Frame 0: T * R * S applied to (1, 0, 0): scale -> (2, 0, 0), rotate 90 about z -> (0, 2, 0), +
  // T.
  expect_near(glm::vec3(s.frame_state(0).transforms[0] * glm::vec4(1, 0, 0, 1)), {1, 4, 3});
  // Frame 1 (t = 1): halfway, T = (2, 2, 3), S = (3, 1, 1) -> (0, 3, 0) + T.
  expect_near(glm::vec3(s.frame_state(1).transforms[0] * glm::vec4(1, 0, 0, 1)), {2, 5, 3});
  // The untracked instance keeps its transform.
  EXPECT_EQ(s.frame_state(1).transforms[1], s.instances[1].transform);
}

TEST(SceneFrameState, LodScheduleUsesTheLatestKeyAtOrBeforeTheTime) {
  Scene s = small_scene();
  s.animation.frames_per_second = 1.0f;
  s.animation.lod_schedule = {LodKey{1.0f, 1, 0}, LodKey{3.0f, 1, 1}, LodKey{3.0f, 0, 0}};
  EXPECT_EQ(s.frame_state(0).lods, (std::vector<uint32_t>{0, 1}));  // Instance::lod before any key
  EXPECT_EQ(s.frame_state(1).lods, (std::vector<uint32_t>{0, 0}));
  EXPECT_EQ(s.frame_state(2).lods, (std::vector<uint32_t>{0, 0}));
  EXPECT_EQ(s.frame_state(3).lods, (std::vector<uint32_t>{0, 1}));
  EXPECT_EQ(s.frame_state(90).lods, (std::vector<uint32_t>{0, 1}));
}

TEST(SceneFrameState, AnimationDurationIsTheLastKey) {
  Scene s = small_scene();
  EXPECT_EQ(animation_duration(s.animation), 0.0f);
  s.animation.lod_schedule = {LodKey{2.5f, 0, 0}};
  s.animation.camera = {CameraKey{1.0f, {}, {}}};
  EXPECT_EQ(animation_duration(s.animation), 2.5f);
}

TEST(SceneValidate, AcceptsAWellFormedScene) {
  EXPECT_EQ(validate_message(small_scene()), "");
}

TEST(SceneValidate, NamesTheOffendingField) {
  struct Case {
    const char* expected;
    void (*edit)(Scene&);
  };
  const Case cases[] = {
      {"instances[1].lod_meshes[1] = 9 is out of range (2 meshes)",
       [](Scene& s) { s.instances[1].lod_meshes[1] = 9; }},
      {"instances[0].lod_meshes is empty", [](Scene& s) { s.instances[0].lod_meshes.clear(); }},
      {"instances[0].lod = 1 is out of range (1 LoD levels)",
       [](Scene& s) { s.instances[0].lod = 1; }},
      {"instances[1].transform",
       [](Scene& s) { s.instances[1].transform[3][0] = std::numeric_limits<float>::infinity(); }},
      {"meshes[1].primitives[0].material = 3 is out of range (1 materials)",
       [](Scene& s) { s.meshes[1].primitives[0].material = 3; }},
      {"meshes[0].primitives[0].indices[2] = 3 is out of range (3 vertices)",
       [](Scene& s) { s.meshes[0].primitives[0].indices[2] = 3; }},
      {"meshes[0].primitives[0].indices has 4 entries, not a multiple of 3",
       [](Scene& s) { s.meshes[0].primitives[0].indices.push_back(0); }},
      {"meshes[0].primitives[0].normals has 2 entries",
       [](Scene& s) { s.meshes[0].primitives[0].normals.pop_back(); }},
      {"meshes[0].primitives[0].uvs has 4 entries",
       [](Scene& s) { s.meshes[0].primitives[0].uvs.emplace_back(); }},
      {"meshes[0].primitives[0].positions[1] is not finite",
       [](Scene& s) { s.meshes[0].primitives[0].positions[1].y = std::nanf(""); }},
      {"meshes[0].primitives[0].normals[0] is not unit length",
       [](Scene& s) {
         s.meshes[0].primitives[0].normals[0] = {0, 0, 2};
       }},
      {"materials[0].roughness", [](Scene& s) { s.materials[0].roughness = 1.5f; }},
      {"materials[0].emission is negative", [](Scene& s) { s.materials[0].emission.g = -1.0f; }},
      {"camera.yfov", [](Scene& s) { s.camera.yfov = 3.2f; }},
      {"camera.yfov", [](Scene& s) { s.camera.yfov = 0.0f; }},
      {"camera.orientation is a zero quaternion",
       [](Scene& s) { s.camera.orientation = glm::quat(0, 0, 0, 0); }},
      {"environment.radiance is not finite",
       [](Scene& s) { s.environment.radiance.x = std::numeric_limits<float>::infinity(); }},
      {"animation.frames_per_second is not positive",
       [](Scene& s) { s.animation.frames_per_second = 0.0f; }},
      {"animation.tracks[0].instance = 2 is out of range (2 instances)",
       [](Scene& s) {
         s.animation.tracks.push_back(InstanceTrack{2, {TransformKey{}}});
       }},
      {"animation.tracks[1].instance = 0 has a second track",
       [](Scene& s) {
         s.animation.tracks = {InstanceTrack{0, {}}, InstanceTrack{0, {}}};
       }},
      {"animation.tracks[0].keys[1].time is earlier",
       [](Scene& s) {
         s.animation.tracks.push_back(InstanceTrack{0, {TransformKey{1.0f}, TransformKey{0.5f}}});
       }},
      {"animation.camera[0].position is not finite",
       [](Scene& s) {
         s.animation.camera = {CameraKey{0.0f, glm::vec3(std::nanf(""))}};
       }},
      {"animation.lod_schedule[0].level = 2 is out of range (2 LoD levels)",
       [](Scene& s) {
         s.animation.lod_schedule = {LodKey{0.0f, 1, 2}};
       }},
      {"animation.lod_schedule[0].instance = 5 is out of range (2 instances)",
       [](Scene& s) {
         s.animation.lod_schedule = {LodKey{0.0f, 5, 0}};
       }},
      {"animation.lod_schedule[1].time is earlier",
       [](Scene& s) {
         s.animation.lod_schedule = {LodKey{1.0f, 0, 0}, LodKey{0.0f, 0, 0}};
       }},
  };
  for (const Case& c : cases) {
    Scene s = small_scene();
    c.edit(s);
    const std::string message = validate_message(s);
    EXPECT_NE(message.find(c.expected), std::string::npos)
        << "expected '" << c.expected << "' in '" << message << "'";
  }
}

TEST(SceneTriangleCount, CountsEveryMeshAndPrimitive) {
  EXPECT_EQ(small_scene().triangle_count(), 3u);
}

TEST(SceneTransform, ComposeDecomposeRoundTrip) {
  const glm::vec3 t(1.5f, -2.0f, 3.25f);
  const glm::quat r = glm::normalize(glm::quat(0.8f, 0.2f, -0.4f, 0.1f));
  const glm::vec3 s(2.0f, 0.5f, 3.0f);
  const TransformKey key = decompose_trs(compose_trs(t, r, s));
  expect_near(key.translation, t);
  expect_near(key.scale, s);
  EXPECT_NEAR(std::abs(glm::dot(key.rotation, r)), 1.0f, 1e-5f);
  // A mirror shows up as a negative x scale, and composing back gives the same matrix.
  const glm::mat4 mirror = glm::scale(glm::mat4(1.0f), {-1.0f, 1.0f, 1.0f});
  EXPECT_LT(decompose_trs(mirror).scale.x, 0.0f);
  const glm::mat4 back = compose_trs(decompose_trs(mirror));
  for (int c = 0; c < 4; ++c) expect_near(glm::vec3(back[c]), glm::vec3(mirror[c]));
}

}  // namespace
}  // namespace strata::scene
