// export_glb / load_glb_bytes / load_gltf_file: every built-in scene comes back equal, and so do
// skins, morph targets and their tracks.
#include <algorithm>
#include <filesystem>
#include <string>

#include <glm/gtc/matrix_transform.hpp>
#include <glm/gtc/quaternion.hpp>
#include <gtest/gtest.h>

#include "scene/scene_io.h"

namespace strata::scene {
namespace {

// Names the first part that differs, so a failing round trip says where.
std::string first_difference(const Scene& a, const Scene& b) {
  if (a.name != b.name) return "name";
  if (a.materials != b.materials) {
    if (a.materials.size() != b.materials.size()) return "materials.size";
    for (size_t i = 0; i < a.materials.size(); ++i) {
      if (!(a.materials[i] == b.materials[i])) return "materials[" + std::to_string(i) + "]";
    }
  }
  if (a.meshes != b.meshes) {
    if (a.meshes.size() != b.meshes.size()) return "meshes.size";
    for (size_t i = 0; i < a.meshes.size(); ++i) {
      if (!(a.meshes[i] == b.meshes[i])) return "meshes[" + std::to_string(i) + "]";
    }
  }
  if (a.instances != b.instances) {
    if (a.instances.size() != b.instances.size()) return "instances.size";
    for (size_t i = 0; i < a.instances.size(); ++i) {
      if (!(a.instances[i] == b.instances[i])) return "instances[" + std::to_string(i) + "]";
    }
  }
  if (!(a.camera == b.camera)) return "camera";
  if (!(a.environment == b.environment)) return "environment";
  if (a.animation.frames_per_second != b.animation.frames_per_second)
    return "animation.frames_per_second";
  if (a.animation.camera != b.animation.camera) return "animation.camera";
  if (a.animation.tracks != b.animation.tracks) {
    if (a.animation.tracks.size() != b.animation.tracks.size()) return "animation.tracks.size";
    for (size_t i = 0; i < a.animation.tracks.size(); ++i) {
      if (!(a.animation.tracks[i] == b.animation.tracks[i]))
        return "animation.tracks[" + std::to_string(i) + "]";
    }
  }
  if (a.animation.lod_schedule != b.animation.lod_schedule) return "animation.lod_schedule";
  if (a.lights != b.lights) return "lights";
  if (a.animation.light_tracks != b.animation.light_tracks) return "animation.light_tracks";
  if (a.skins != b.skins) return "skins";
  if (a.animation.joint_tracks != b.animation.joint_tracks) return "animation.joint_tracks";
  if (a.animation.morph_tracks != b.animation.morph_tracks) return "animation.morph_tracks";
  return "";
}

class GltfRoundTrip : public ::testing::TestWithParam<std::string> {};

TEST_P(GltfRoundTrip, ExportedGlbLoadsBackEqual) {
  const Scene original = builtin_scene(GetParam());
  const std::vector<uint8_t> glb = export_glb(original);
  const Scene loaded = load_glb_bytes(glb, GetParam() + ".glb");
  EXPECT_EQ(first_difference(original, loaded), "");
  EXPECT_TRUE(loaded == original);
  EXPECT_EQ(export_glb(loaded), glb);  // and exporting is deterministic
}

TEST_P(GltfRoundTrip, ThroughAFile) {
  const Scene original = builtin_scene(GetParam());
  const std::filesystem::path dir =
      std::filesystem::temp_directory_path() / "strata_gltf_roundtrip";
  std::filesystem::create_directories(dir);
  const std::filesystem::path path = dir / (GetParam() + ".glb");
  export_glb_file(original, path);
  const Scene loaded = load_gltf_file(path);
  EXPECT_EQ(first_difference(original, loaded), "");
  EXPECT_TRUE(loaded == original);
  EXPECT_TRUE(load_scene(path.string()) == original);
  std::filesystem::remove(path);
}

// gtest names may not contain '-'.
std::string param_name(const ::testing::TestParamInfo<std::string>& param) {
  std::string name = param.param;
  std::replace(name.begin(), name.end(), '-', '_');
  return name;
}

INSTANTIATE_TEST_SUITE_P(Gltf, GltfRoundTrip, ::testing::ValuesIn(builtin_scene_names()),
                         param_name);

// A light's track is written as its node's T/R/S channels (its rest transform in extras) and comes
// back as the same track: a lamp carried around cornell-lamps, turning as it goes.
TEST(GltfExport, ALightTrackComesBackEqual) {
  Scene original = builtin_scene("cornell-lamps");
  ASSERT_FALSE(original.lights.empty());
  LightTrack track{0, {}};
  for (int k = 0; k < 4; ++k) {
    TransformKey key;
    key.time = 0.5f * float(k);
    key.translation = glm::vec3(0.1f * float(k), 0.9f, -0.05f * float(k));
    key.rotation = glm::angleAxis(0.4f * float(k), glm::normalize(glm::vec3(0.2f, 1.0f, 0.1f)));
    key.scale = glm::vec3(1.0f);
    track.keys.push_back(key);
  }
  original.animation.light_tracks.push_back(track);
  original.validate();
  const std::vector<uint8_t> glb = export_glb(original);
  const Scene loaded = load_glb_bytes(glb, "cornell-lamps-moving.glb");
  EXPECT_EQ(first_difference(original, loaded), "");
  EXPECT_TRUE(loaded == original);
  EXPECT_EQ(export_glb(loaded), glb);
  // And the light moves: frame 15 (0.5 s at 30 fps) puts it at the second key.
  EXPECT_NE(loaded.frame_state(0).lights.at(0), loaded.frame_state(15).lights.at(0));
}

// cornell with a skinned box (two joints: one at rest, written as a matrix, one with a track,
// written as TRS with its exact rest matrix in extras) and a morphing box (two targets, one without
// normal deltas; mesh weights, other instance weights, and a morph track).
Scene skinned_and_morphing_cornell() {
  Scene s = builtin_scene("cornell");
  size_t skinned = s.instances.size(), morphing = s.instances.size();
  for (size_t i = 0; i < s.instances.size(); ++i) {
    if (s.instances[i].lod_meshes.size() != 1) continue;
    if (skinned == s.instances.size()) {
      skinned = i;
    } else if (s.instances[i].lod_meshes[0] != s.instances[skinned].lod_meshes[0]) {
      morphing = i;
      break;
    }
  }
  EXPECT_LT(morphing, s.instances.size()) << "cornell needs two instances of different meshes";
  if (morphing == s.instances.size()) return s;
  Skin skin;
  skin.name = "rig";
  const glm::mat4 turn = glm::mat4_cast(glm::angleAxis(0.3f, glm::vec3(0, 0, 1)));
  skin.joints = {glm::translate(glm::mat4(1.0f), {0.1f, 0.2f, 0.3f}),
                 glm::translate(glm::mat4(1.0f), {0.0f, 1.0f, 0.0f}) * turn};
  for (const glm::mat4& j : skin.joints) skin.inverse_bind.push_back(glm::inverse(j));
  s.skins.push_back(skin);
  s.instances[skinned].skin = 0;
  for (Primitive& p : s.meshes[s.instances[skinned].lod_meshes[0]].primitives) {
    for (size_t v = 0; v < p.positions.size(); ++v) {
      p.joints.emplace_back(v % 2, 1 - v % 2, 0, 0);
      p.weights.emplace_back(0.75f, 0.25f, 0.0f, 0.0f);
    }
  }
  JointTrack joint{0, 1, {}};
  for (int k = 0; k < 3; ++k) {
    TransformKey key;
    key.time = 0.5f * float(k);
    key.translation = glm::vec3(0.0f, 1.0f, 0.1f * float(k));
    key.rotation = glm::angleAxis(0.3f + 0.2f * float(k), glm::vec3(0, 0, 1));
    joint.keys.push_back(key);
  }
  s.animation.joint_tracks.push_back(joint);

  Mesh& mesh = s.meshes[s.instances[morphing].lod_meshes[0]];
  mesh.weights = {0.1f, 0.0f};
  for (Primitive& p : mesh.primitives) {
    MorphTarget lift, shift;
    for (size_t v = 0; v < p.positions.size(); ++v) {
      lift.positions.emplace_back(0.0f, 0.2f, 0.0f);
      lift.normals.emplace_back(0.01f * float(v % 3), 0.0f, 0.0f);
      shift.positions.emplace_back(0.05f * float(v % 4), 0.0f, 0.0f);
    }
    p.targets = {lift, shift};
  }
  s.instances[morphing].morph_weights = {0.5f, 0.25f};
  s.animation.morph_tracks.push_back(
      MorphTrack{uint32_t(morphing), {{0.0f, {0.0f, 1.0f}}, {1.0f, {1.0f, 0.5f}}, {2.0f, {0.25f, 0.0f}}}});
  s.validate();
  return s;
}

TEST(GltfExport, SkinsAndMorphTargetsComeBackEqual) {
  const Scene original = skinned_and_morphing_cornell();
  ASSERT_EQ(original.skins.size(), 1u);
  const std::vector<uint8_t> glb = export_glb(original);
  const Scene loaded = load_glb_bytes(glb, "cornell-characters.glb");
  EXPECT_EQ(first_difference(original, loaded), "");
  EXPECT_TRUE(loaded == original);
  EXPECT_EQ(export_glb(loaded), glb);
  EXPECT_TRUE(loaded.ignored_features.empty());
  // And both deform over time: the joint's and the weights' keys differ at frames 0 and 30.
  EXPECT_NE(loaded.frame_state(0).joints, loaded.frame_state(30).joints);
  EXPECT_NE(loaded.frame_state(0).morph_weights, loaded.frame_state(30).morph_weights);
}

TEST(GltfExport, RejectsAnInvalidScene) {
  Scene s = builtin_scene("cornell");
  s.instances[0].lod_meshes[0] = 99;
  EXPECT_THROW(export_glb(s), SceneError);
  EXPECT_THROW(export_glb_file(builtin_scene("cornell"), "/nonexistent-dir/x.glb"), SceneError);
}

}  // namespace
}  // namespace strata::scene
