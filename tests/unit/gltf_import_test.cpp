// The glTF loader on small hand-built files: hierarchy flattening, materials, MSFT_lod, missing
// attributes, index formats, cameras and animations.
#include <cmath>
#include <filesystem>
#include <fstream>

#include <glm/gtc/matrix_transform.hpp>
#include <gtest/gtest.h>

#include "gltf_test_builder.h"
#include "scene/scene_io.h"

namespace strata::scene {
namespace {

using nlohmann::json;
using testing::TestGltf;

constexpr float kHalfPi = 1.57079632679f;

Scene load(const TestGltf& g) {
  return load_glb_bytes(g.text_bytes(), "test.gltf");
}

void expect_near(const glm::vec3& a, const glm::vec3& b, float eps = 1e-5f) {
  EXPECT_NEAR(a.x, b.x, eps);
  EXPECT_NEAR(a.y, b.y, eps);
  EXPECT_NEAR(a.z, b.z, eps);
}

glm::vec3 apply(const glm::mat4& m, const glm::vec3& p) {
  return glm::vec3(m * glm::vec4(p, 1.0f));
}

TEST(GltfImport, FlattensTrsAndMatrixHierarchies) {
  TestGltf g;
  const int mesh = g.quad_mesh();
  // child: matrix = translate(0, 0, 1) * scale(2); parent: T (1, 0, 0), R 90 degrees about +Y.
  const int child =
      g.node({{"mesh", mesh}, {"matrix", {2, 0, 0, 0, 0, 2, 0, 0, 0, 0, 2, 0, 0, 0, 1, 1}}});
  const float s = std::sqrt(0.5f);
  g.node({{"translation", {1, 0, 0}}, {"rotation", {0, s, 0, s}}, {"children", {child}}});
  g.scene({1});
  const Scene scene = load(g);
  ASSERT_EQ(scene.instances.size(), 1u);
  // (1, 0, 0) -> scale (2, 0, 0) -> +z (2, 0, 1) -> rotate about y: (1, 0, -2) -> +T (2, 0, -2).
  expect_near(apply(scene.instances[0].transform, {1, 0, 0}), {2, 0, -2});
  expect_near(apply(scene.instances[0].transform, {0, 0, 0}), {2, 0, 0});
}

TEST(GltfImport, UsesOnlyTheDefaultSceneOrElseAllRoots) {
  TestGltf g;
  const int mesh = g.quad_mesh();
  g.node({{"mesh", mesh}, {"name", "in_scene_0"}});
  g.node({{"mesh", mesh}, {"name", "in_scene_1"}});
  g.scene({0});
  g.scene({1});
  g.doc["scene"] = 1;
  Scene scene = load(g);
  ASSERT_EQ(scene.instances.size(), 1u);
  EXPECT_EQ(scene.instances[0].name, "in_scene_1");

  g.doc.erase("scene");
  scene = load(g);
  ASSERT_EQ(scene.instances.size(), 1u);
  EXPECT_EQ(scene.instances[0].name, "in_scene_0");

  g.doc.erase("scenes");
  scene = load(g);
  EXPECT_EQ(scene.instances.size(), 2u);
}

TEST(GltfImport, ReadsMaterialFactorsAndEmissiveStrength) {
  TestGltf g;
  g.doc["materials"] = json::array(
      {{{"name", "lamp"},
        {"pbrMetallicRoughness",
         {{"baseColorFactor", {0.5, 0.25, 0.125, 1.0}},
          {"metallicFactor", 0.75},
          {"roughnessFactor", 0.5}}},
        {"emissiveFactor", {1.0, 0.5, 0.25}},
        {"extensions", {{"KHR_materials_emissive_strength", {{"emissiveStrength", 8.0}}}}},
        {"doubleSided", true}}});
  g.doc["extensionsUsed"] = {"KHR_materials_emissive_strength"};
  const int mesh = g.mesh({{"attributes", {{"POSITION", g.quad_positions()}}},
                           {"indices", g.quad_indices()},
                           {"material", 0}});
  g.node({{"mesh", mesh}});
  const Scene scene = load(g);
  ASSERT_EQ(scene.materials.size(), 1u);
  const Material& m = scene.materials[0];
  EXPECT_EQ(m.name, "lamp");
  EXPECT_EQ(m.base_color, glm::vec3(0.5f, 0.25f, 0.125f));
  EXPECT_EQ(m.metallic, 0.75f);
  EXPECT_EQ(m.roughness, 0.5f);
  EXPECT_EQ(m.emission, glm::vec3(8.0f, 4.0f, 2.0f));
  EXPECT_TRUE(m.double_sided);
  // A file with an emitter and no strata extras keeps a black environment.
  EXPECT_EQ(scene.environment.radiance, glm::vec3(0.0f));
}

TEST(GltfImport, PrimitivesWithoutMaterialGetADefaultOne) {
  TestGltf g;
  g.doc["materials"] = json::array({{{"name", "given"}}});
  const int mesh = g.quad_mesh();
  g.node({{"mesh", mesh}});
  const Scene scene = load(g);
  ASSERT_EQ(scene.materials.size(), 2u);
  EXPECT_EQ(scene.materials[1].name, "default");
  EXPECT_EQ(scene.meshes[0].primitives[0].material, 1u);
  // Nothing emits, so the scene gets a white environment to be visible at all.
  EXPECT_EQ(scene.environment.radiance, glm::vec3(1.0f));
}

TEST(GltfImport, GeneratesMissingNormalsAndZeroUvs) {
  TestGltf g;
  g.node({{"mesh", g.quad_mesh()}});
  const Scene scene = load(g);
  const Primitive& p = scene.meshes[0].primitives[0];
  ASSERT_EQ(p.normals.size(), 4u);
  for (const glm::vec3& n : p.normals) EXPECT_EQ(n, glm::vec3(0, 0, 1));
  for (const glm::vec2& uv : p.uvs) EXPECT_EQ(uv, glm::vec2(0.0f));
}

TEST(GltfImport, KeepsGivenNormalsAndNormalizedUvs) {
  TestGltf g;
  const int normals = g.floats({0, 0, 1, 0, 0, 1, 0, 0.6f, 0.8f, 0, 0, 2}, "VEC3", 3);
  const std::vector<uint16_t> uv16 = {0, 0, 65535, 0, 65535, 65535, 0, 32768};
  const int uvs = g.accessor(uv16.data(), uv16.size() * 2, 5123, "VEC2", 4, /*normalized=*/true);
  const int mesh = g.mesh(
      {{"attributes", {{"POSITION", g.quad_positions()}, {"NORMAL", normals}, {"TEXCOORD_0", uvs}}},
       {"indices", g.quad_indices()}});
  g.node({{"mesh", mesh}});
  const Scene scene = load(g);
  const Primitive& p = scene.meshes[0].primitives[0];
  EXPECT_EQ(p.normals[2], glm::vec3(0, 0.6f, 0.8f));  // unit: kept bit for bit
  EXPECT_EQ(p.normals[3], glm::vec3(0, 0, 1));        // length 2: normalised
  EXPECT_EQ(p.uvs[2], glm::vec2(1.0f, 1.0f));
  EXPECT_FLOAT_EQ(p.uvs[3].y, 32768.0f / 65535.0f);
}

TEST(GltfImport, ReadsByteShortAndMissingIndices) {
  TestGltf g;
  const int positions = g.quad_positions();
  const int m8 =
      g.mesh({{"attributes", {{"POSITION", positions}}}, {"indices", g.u8({0, 1, 2, 0, 2, 3})}});
  const int m16 =
      g.mesh({{"attributes", {{"POSITION", positions}}}, {"indices", g.u16({0, 1, 2, 0, 2, 3})}});
  const int flat =
      g.mesh({{"attributes", {{"POSITION", g.floats({0, 0, 0, 1, 0, 0, 0, 1, 0}, "VEC3", 3)}}}});
  for (int mesh : {m8, m16, flat}) g.node({{"mesh", mesh}});
  const Scene scene = load(g);
  EXPECT_EQ(scene.meshes[0].primitives[0].indices, (std::vector<uint32_t>{0, 1, 2, 0, 2, 3}));
  EXPECT_EQ(scene.meshes[1].primitives[0].indices, (std::vector<uint32_t>{0, 1, 2, 0, 2, 3}));
  EXPECT_EQ(scene.meshes[2].primitives[0].indices, (std::vector<uint32_t>{0, 1, 2}));
}

TEST(GltfImport, MsftLodNodesBecomeLevelsNotInstances) {
  TestGltf g;
  const int fine = g.quad_mesh(), mid = g.quad_mesh(), coarse = g.quad_mesh();
  g.node({{"mesh", fine}, {"name", "object"}, {"extensions", {{"MSFT_lod", {{"ids", {1, 2}}}}}}});
  g.node({{"mesh", mid}, {"name", "object_lod1"}});
  g.node({{"mesh", coarse}, {"name", "object_lod2"}});
  g.doc["extensionsUsed"] = {"MSFT_lod"};
  g.scene({0, 1});  // a LoD node listed in the scene must still not become an instance
  const Scene scene = load(g);
  ASSERT_EQ(scene.instances.size(), 1u);
  EXPECT_EQ(scene.instances[0].lod_meshes, (std::vector<uint32_t>{0, 1, 2}));
}

TEST(GltfImport, FirstPerspectiveCameraNodeBecomesTheCamera) {
  TestGltf g;
  g.node({{"mesh", g.quad_mesh()}});
  g.doc["cameras"] =
      json::array({{{"type", "perspective"},
                    {"perspective", {{"yfov", 0.5}, {"znear", 0.1}, {"aspectRatio", 2.0}}}}});
  const float s = std::sqrt(0.5f);
  const int cam = g.node({{"camera", 0}, {"translation", {0, 0, 4}}});
  g.node({{"rotation", {0, s, 0, s}}, {"translation", {1, 2, 3}}, {"children", {cam}}});
  g.scene({0, 2});
  const Scene scene = load(g);
  EXPECT_FLOAT_EQ(scene.camera.yfov, 0.5f);
  expect_near(scene.camera.position,
              {5, 2, 3});  // (0, 0, 4) turned 90 degrees about y is (4, 0, 0)
  expect_near(scene.camera.orientation * glm::vec3(0, 0, -1), {-1, 0, 0});
}

TEST(GltfImport, WithoutACameraFramesTheScene) {
  TestGltf g;
  g.node({{"mesh", g.quad_mesh()}});
  const Scene scene = load(g);
  expect_near(glm::vec3(scene.camera.position.x, scene.camera.position.y, 0), {0.5f, 0.5f, 0});
  EXPECT_GT(scene.camera.position.z, 0.5f);
}

// A translation channel on a parent moves both children; keys are world transforms.
TEST(GltfImport, ParentAnimationMovesEveryInstanceUnderIt) {
  TestGltf g;
  const int mesh = g.quad_mesh();
  const int a = g.node({{"mesh", mesh}, {"translation", {1, 0, 0}}});
  const int b = g.node({{"mesh", mesh}, {"translation", {0, 1, 0}}});
  g.node({{"children", {a, b}}, {"scale", {2, 2, 2}}});
  g.scene({2});
  const int times = g.floats({0.0f, 1.0f}, "SCALAR", 1);
  const int values = g.floats({0, 0, 0, 10, 0, 0}, "VEC3", 3);
  g.doc["animations"] = json::array(
      {{{"samplers", {{{"input", times}, {"output", values}}}},
        {"channels", {{{"sampler", 0}, {"target", {{"node", 2}, {"path", "translation"}}}}}}}});
  const Scene scene = load(g);
  ASSERT_EQ(scene.animation.tracks.size(), 2u);
  for (const InstanceTrack& track : scene.animation.tracks) ASSERT_EQ(track.keys.size(), 2u);
  expect_near(scene.animation.tracks[0].keys[1].translation, {12, 0, 0});
  expect_near(scene.animation.tracks[1].keys[1].translation, {10, 2, 0});
  expect_near(scene.animation.tracks[0].keys[1].scale, {2, 2, 2});
  scene.validate();
  // Halfway through (frame 15 at 30 fps) the first child is at 5 + 2.
  expect_near(apply(scene.frame_state(15).transforms[0], {0, 0, 0}), {7, 0, 0});
}

TEST(GltfImport, StepSamplersHoldTheirValueUntilTheNextKey) {
  TestGltf g;
  g.node({{"mesh", g.quad_mesh()}});
  const int times = g.floats({0.0f, 1.0f}, "SCALAR", 1);
  const int values = g.floats({0, 0, 0, 0, 4, 0}, "VEC3", 3);
  g.doc["animations"] = json::array(
      {{{"samplers", {{{"input", times}, {"output", values}, {"interpolation", "STEP"}}}},
        {"channels", {{{"sampler", 0}, {"target", {{"node", 0}, {"path", "translation"}}}}}}}});
  const Scene scene = load(g);
  ASSERT_EQ(scene.animation.tracks.size(), 1u);
  EXPECT_EQ(scene.animation.tracks[0].keys.size(), 3u);  // 0, just before 1, 1
  expect_near(apply(scene.frame_state(29).transforms[0], {0, 0, 0}), {0, 0, 0});
  expect_near(apply(scene.frame_state(30).transforms[0], {0, 0, 0}), {0, 4, 0});
}

TEST(GltfImport, GlbAndExternalBuffersInTheSameDirectoryLoad) {
  TestGltf g;
  g.node({{"mesh", g.quad_mesh()}});
  const Scene from_text = load(g);
  Scene from_glb = load_glb_bytes(g.glb(), "test.glb");
  EXPECT_EQ(from_glb.name, "test.glb");  // no scene name in the file: the label stands in
  from_glb.name = from_text.name;
  EXPECT_EQ(from_glb, from_text);

  const std::filesystem::path dir = std::filesystem::temp_directory_path() / "strata_gltf_external";
  std::filesystem::create_directories(dir);
  std::ofstream(dir / "data.bin", std::ios::binary)
      .write(reinterpret_cast<const char*>(g.bin.data()),
             static_cast<std::streamsize>(g.bin.size()));
  json doc = g.doc;
  doc["buffers"] = json::array({{{"byteLength", g.bin.size()}, {"uri", "data.bin"}}});
  std::ofstream(dir / "scene.gltf") << doc.dump();
  Scene from_file = load_gltf_file(dir / "scene.gltf");
  EXPECT_EQ(from_file.name, "scene");  // the file's stem
  from_file.name = from_text.name;
  EXPECT_EQ(from_file, from_text);
  std::filesystem::remove_all(dir);
}

}  // namespace
}  // namespace strata::scene
