// export_glb / load_glb_bytes / load_gltf_file: every built-in scene comes back equal.
#include <algorithm>
#include <filesystem>
#include <string>

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

TEST(GltfExport, RejectsAnInvalidScene) {
  Scene s = builtin_scene("cornell");
  s.instances[0].lod_meshes[0] = 99;
  EXPECT_THROW(export_glb(s), SceneError);
  EXPECT_THROW(export_glb_file(builtin_scene("cornell"), "/nonexistent-dir/x.glb"), SceneError);
}

}  // namespace
}  // namespace strata::scene
