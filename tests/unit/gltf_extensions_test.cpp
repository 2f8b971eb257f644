// glTF extensions and features strata does not render: required ones refuse the file by name, used
// ones load and are listed in Scene::ignored_features with the objects that carry them; a file
// without geometry is refused by name; triangle strips and fans become triangle lists.
#include <string>

#include <gtest/gtest.h>

#include "gltf_test_builder.h"
#include "scene/scene_io.h"
#include "scene/unrendered.h"

namespace strata::scene {
namespace {

using nlohmann::json;
using testing::TestGltf;

std::string error_of(const TestGltf& g) {
  try {
    load_glb_bytes(g.glb(), "file.glb");
  } catch (const SceneError& e) {
    return e.what();
  }
  return "(loaded without error)";
}

std::string ignored_of(const TestGltf& g) {
  std::string s;
  for (const std::string& f : unrendered_features(load_glb_bytes(g.glb(), "file.glb"))) s += f + "\n";
  return s;
}

TestGltf quad_file() {
  TestGltf g;
  g.node({{"mesh", g.quad_mesh()}});
  return g;
}

::testing::AssertionResult contains(const std::string& text, const std::string& expected) {
  if (text.find(expected) != std::string::npos) return ::testing::AssertionSuccess();
  return ::testing::AssertionFailure() << "expected '" << expected << "' in '" << text << "'";
}

TEST(GltfExtensions, RequiredExtensionsStrataDoesNotRenderRefuseTheFileByName) {
  TestGltf g = quad_file();
  g.doc["extensionsUsed"] = {"KHR_draco_mesh_compression"};
  g.doc["extensionsRequired"] = {"KHR_draco_mesh_compression"};
  EXPECT_EQ(error_of(g),
            "file.glb: extensionsRequired lists KHR_draco_mesh_compression (Draco-compressed "
            "meshes), which strata does not render");

  g.doc["extensionsRequired"] = {"EXT_meshopt_compression", "KHR_texture_basisu", "EXT_made_up"};
  EXPECT_TRUE(contains(error_of(g),
                       "extensionsRequired lists EXT_meshopt_compression (meshoptimizer-compressed "
                       "buffers), KHR_texture_basisu (KTX2 / Basis Universal textures) and "
                       "EXT_made_up, which strata does not render"));

  // The same list in the .gltf text form, checked before tinygltf sees the file.
  EXPECT_THROW(load_glb_bytes(g.text_bytes(), "file.gltf"), SceneError);

  // Required extensions that strata renders are accepted.
  g.doc["extensionsRequired"] = {"KHR_materials_emissive_strength"};
  EXPECT_NO_THROW(load_glb_bytes(g.glb(), "file.glb"));
}

TEST(GltfExtensions, UsedExtensionsAreListedWithTheObjectsCarryingThem) {
  TestGltf g = quad_file();
  g.doc["extensionsUsed"] = {"KHR_materials_clearcoat", "KHR_materials_emissive_strength",
                             "EXT_made_up", "KHR_materials_sheen"};
  for (int i = 0; i < 3; ++i) {
    g.doc["materials"].push_back(
        {{"extensions", {{"KHR_materials_clearcoat", {{"clearcoatFactor", 1.0}}}}}});
  }
  g.doc["materials"][0]["extensions"]["KHR_materials_emissive_strength"] = {{"emissiveStrength", 2}};
  g.doc["nodes"][0]["extensions"] = {{"EXT_made_up", json::object()}};
  g.doc["meshes"][0]["primitives"][0]["material"] = 0;
  const std::string ignored = ignored_of(g);
  EXPECT_TRUE(contains(ignored, "KHR_materials_clearcoat on 3 materials (rendered without the coat)\n"));
  EXPECT_TRUE(contains(ignored, "EXT_made_up on 1 node\n"));
  EXPECT_TRUE(contains(ignored, "KHR_materials_sheen (listed in extensionsUsed, on no object)\n"));
  EXPECT_FALSE(contains(ignored, "emissive_strength"));  // rendered
}

// Skins and morph targets are rendered and not listed; a target's TANGENT deltas are not applied.
TEST(GltfExtensions, MorphTangentDeltasAndVertexColoursAreListed) {
  TestGltf g;
  const int positions = g.quad_positions();
  const int colours = g.floats(std::vector<float>(16, 1.0f), "VEC4", 4);
  const int target = g.floats(std::vector<float>(12, 0.1f), "VEC3", 3);
  const int joints = g.accessor(std::vector<uint8_t>(16, 0).data(), 16, 5121, "VEC4", 4);
  const int weights = g.floats({1, 0, 0, 0, 1, 0, 0, 0, 1, 0, 0, 0, 1, 0, 0, 0}, "VEC4", 4);
  g.node({{"mesh", g.mesh({{"attributes", {{"POSITION", positions}, {"COLOR_0", colours},
                                           {"JOINTS_0", joints}, {"WEIGHTS_0", weights}}},
                           {"indices", g.quad_indices()},
                           {"targets", json::array({{{"POSITION", target}, {"TANGENT", target}}})}})},
          {"skin", 0}});
  g.node({{"name", "joint"}});
  g.doc["skins"] = json::array({{{"joints", {1}}}});
  const std::string ignored = ignored_of(g);
  EXPECT_TRUE(contains(ignored, "morph target TANGENT deltas on 1 mesh (not applied: the rest pose's TANGENT is used)\n"));
  EXPECT_TRUE(contains(ignored, "COLOR_0 on 1 primitive (vertex colours are not rendered)\n"));
  EXPECT_FALSE(contains(ignored, "skin"));
  EXPECT_FALSE(contains(ignored, "morph targets"));
}

TEST(GltfExtensions, FilesWithoutGeometryAreRefusedByName) {
  TestGltf g;
  g.node({{"name", "empty"}});
  g.scene({0});
  EXPECT_EQ(error_of(g), "file.glb: the scene has no geometry: none of the nodes of scenes[0] has a mesh");

  g = TestGltf();
  g.doc["meshes"] = json::array({{{"primitives", json::array()}}});
  g.node({{"mesh", 0}});
  EXPECT_TRUE(contains(error_of(g), "file.glb: meshes[0].primitives is empty or not an array"));

  g = TestGltf();
  g.node({{"mesh", g.mesh({{"attributes", {{"POSITION", g.quad_positions()}}},
                           {"indices", g.u32({})}})}});
  EXPECT_TRUE(contains(error_of(g), "the scene has no geometry: the meshes of its 1 instance have no triangles"));
}

TEST(GltfExtensions, TriangleStripsAndFansBecomeTriangleListsWithTheirWinding) {
  TestGltf g;
  g.node({{"mesh", g.mesh({{"attributes", {{"POSITION", g.quad_positions()}}},
                           {"indices", g.u32({0, 1, 3, 2})},
                           {"mode", 5}})}});
  Scene strip = load_glb_bytes(g.glb(), "strip.glb");
  std::vector<uint32_t> indices = strip.meshes[0].primitives[0].indices;
  ASSERT_EQ(indices.size(), 6u);
  // Triangles {v0,v1,v2} = {0,1,3} and {v1,v3,v2} = {1,2,3} (the odd one swapped), in whatever
  // order the spatial sort left them.
  std::vector<std::vector<uint32_t>> tris = {{indices[0], indices[1], indices[2]},
                                             {indices[3], indices[4], indices[5]}};
  std::sort(tris.begin(), tris.end());
  EXPECT_EQ(tris[0], (std::vector<uint32_t>{0, 1, 3}));
  EXPECT_EQ(tris[1], (std::vector<uint32_t>{1, 2, 3}));
  // Both face +z: the generated normals agree with the winding.
  for (const glm::vec3& n : strip.meshes[0].primitives[0].normals) EXPECT_GT(n.z, 0.99f);

  g = TestGltf();
  g.node({{"mesh", g.mesh({{"attributes", {{"POSITION", g.quad_positions()}}}, {"mode", 6}})}});
  Scene fan = load_glb_bytes(g.glb(), "fan.glb");
  indices = fan.meshes[0].primitives[0].indices;
  ASSERT_EQ(indices.size(), 6u);
  tris = {{indices[0], indices[1], indices[2]}, {indices[3], indices[4], indices[5]}};
  std::sort(tris.begin(), tris.end());
  EXPECT_EQ(tris[0], (std::vector<uint32_t>{1, 2, 0}));
  EXPECT_EQ(tris[1], (std::vector<uint32_t>{2, 3, 0}));
}

}  // namespace
}  // namespace strata::scene
