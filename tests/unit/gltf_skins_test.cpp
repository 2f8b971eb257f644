// glTF skins and morph targets: what the loader reads into the scene model (joints, weights,
// targets, skins, joint and morph tracks), the host deformation of the corpus's samples, every
// refusal naming its field, and Scene::validate's checks of the deformation data.
#include <cmath>
#include <filesystem>
#include <limits>
#include <string>

#include <glm/gtc/matrix_transform.hpp>
#include <gtest/gtest.h>

#include "gltf_test_builder.h"
#include "scene/deform.h"
#include "scene/scene_io.h"
#include "scene/unrendered.h"

namespace strata::scene {
namespace {

namespace fs = std::filesystem;
using nlohmann::json;
using testing::TestGltf;

const fs::path kCorpus = "/usr/share/assimp/models/glTF2";
constexpr float kNaN = std::numeric_limits<float>::quiet_NaN();
constexpr size_t kMaxMorphTargetVerticesForTest = 16'000'000;  // scene/gltf_mesh_deform.h

Scene load(const TestGltf& g) { return load_glb_bytes(g.glb(), "file.glb"); }

std::string error_of(const TestGltf& g) {
  try {
    load(g);
  } catch (const SceneError& e) {
    return e.what();
  }
  return "(loaded without error)";
}

std::string validate_error(const Scene& s) {
  try {
    s.validate();
  } catch (const SceneError& e) {
    return e.what();
  }
  return "(valid)";
}

::testing::AssertionResult contains(const std::string& text, const std::string& expected) {
  if (text.find(expected) != std::string::npos) return ::testing::AssertionSuccess();
  return ::testing::AssertionFailure() << "expected '" << expected << "' in '" << text << "'";
}

std::string joined(const std::vector<std::string>& items) {
  std::string s;
  for (const std::string& item : items) s += item + "\n";
  return s;
}

void expect_near(const glm::vec3& a, const glm::vec3& b, float eps) {
  EXPECT_NEAR(a.x, b.x, eps);
  EXPECT_NEAR(a.y, b.y, eps);
  EXPECT_NEAR(a.z, b.z, eps);
}

// The vertices of primitive `p` of instance `i` at `frame`, deformed on the host (scene/deform.h).
DeformedVertices deformed(const Scene& s, size_t i, size_t p, uint32_t frame) {
  const FrameState state = s.frame_state(frame);
  const Instance& instance = s.instances[i];
  std::vector<SkinningMatrix> skinning;
  if (instance.skin >= 0)
    skinning = skinning_matrices(s.skins[size_t(instance.skin)], state.transforms[i], state.joints[i]);
  return deform_primitive(s.meshes[instance.lod_meshes[0]].primitives[p], skinning, state.morph_weights[i]);
}

// A unit quad skinned to two joints: vertices 0 and 1 (y = 0) follow joint 0 (node 1, at the
// origin), vertices 2 and 3 (y = 1) joint 1 (node 2, node 1's child at y = 1). The inverse bind
// matrices are the joints' inverses, so the rest pose is the bind pose.
TestGltf skinned_quad() {
  TestGltf g;
  const int positions = g.quad_positions();
  const std::vector<uint8_t> joints = {0, 0, 0, 0, 0, 0, 0, 0, 1, 0, 0, 0, 1, 0, 0, 0};
  const int j = g.accessor(joints.data(), joints.size(), 5121, "VEC4", 4);
  const int w = g.floats({1, 0, 0, 0, 1, 0, 0, 0, 1, 0, 0, 0, 1, 0, 0, 0}, "VEC4", 4);
  const int mesh = g.mesh({{"attributes", {{"POSITION", positions}, {"JOINTS_0", j}, {"WEIGHTS_0", w}}},
                           {"indices", g.quad_indices()}},
                          "cloth");
  const int ibm = g.floats({1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1,  //
                            1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, 0, -1, 0, 1},
                           "MAT4", 16);
  g.node({{"mesh", mesh}, {"skin", 0}});
  g.node({{"children", {2}}});
  g.node({{"translation", {0, 1, 0}}});
  g.scene({0, 1});
  g.doc["skins"] = json::array({{{"inverseBindMatrices", ibm}, {"joints", {1, 2}}, {"skeleton", 1}}});
  return g;
}

// A unit quad with normals and two morph targets: "lift" moves every vertex by +1 in z and tilts
// the normals, "shift" moves x by 1 and leaves the normals alone. mesh.weights = (0.25, 0.5).
TestGltf morph_quad() {
  TestGltf g;
  const int positions = g.quad_positions();
  const int normals = g.floats({0, 0, 1, 0, 0, 1, 0, 0, 1, 0, 0, 1}, "VEC3", 3);
  const int lift = g.floats({0, 0, 1, 0, 0, 1, 0, 0, 1, 0, 0, 1}, "VEC3", 3);
  const int tilt = g.floats({1, 0, 0, 1, 0, 0, 1, 0, 0, 1, 0, 0}, "VEC3", 3);
  const int shift = g.floats({1, 0, 0, 1, 0, 0, 1, 0, 0, 1, 0, 0}, "VEC3", 3);
  const int mesh = g.mesh({{"attributes", {{"POSITION", positions}, {"NORMAL", normals}}},
                           {"indices", g.quad_indices()},
                           {"targets", json::array({{{"POSITION", lift}, {"NORMAL", tilt}}, {{"POSITION", shift}}})}},
                          "blob");
  g.doc["meshes"][mesh]["weights"] = {0.25, 0.5};
  g.node({{"mesh", mesh}});
  g.scene({0});
  return g;
}

// One animation with one channel on `node`'s `path`, its sampler reading `input` and `output`.
void animate(TestGltf& g, int node, const std::string& path, int input, int output,
             const std::string& interpolation = "LINEAR") {
  g.doc["animations"] = json::array(
      {{{"channels", json::array({{{"sampler", 0}, {"target", {{"node", node}, {"path", path}}}}})},
        {"samplers", json::array({{{"input", input}, {"output", output}, {"interpolation", interpolation}}})}}});
}

// ---- The corpus (Debian's assimp-testmodels) ----------------------------------------------------

class GltfSkinsCorpus : public ::testing::Test {
 protected:
  void SetUp() override {
    if (!fs::is_directory(kCorpus)) GTEST_SKIP() << kCorpus << " is missing (apt-get install assimp-testmodels)";
  }
};

// simple_skin: a 1 x 2 strip of 10 vertices on two joints (nodes 1 and 2, both at y = 1 at rest);
// node 2 turns about +z, 90 degrees at t = 1 s. Both inverse bind matrices translate by (-0.5, -1,
// 0), so at rest both skinning matrices are a translation by (-0.5, 0, 0): the strip is rigid.
TEST_F(GltfSkinsCorpus, SimpleSkinIsSkinnedAndMoves) {
  const Scene s = load_gltf_file(kCorpus / "simple_skin/simple_skin.gltf");
  EXPECT_EQ(joined(s.ignored_features), "");
  ASSERT_EQ(s.skins.size(), 1u);
  EXPECT_EQ(s.skins[0].joints.size(), 2u);
  EXPECT_EQ(s.skins[0].inverse_bind.size(), 2u);
  ASSERT_EQ(s.instances.size(), 1u);
  EXPECT_EQ(s.instances[0].skin, 0);
  const Primitive& p = s.meshes[0].primitives[0];
  EXPECT_EQ(p.positions.size(), 10u);
  EXPECT_EQ(p.joints.size(), 10u);
  EXPECT_EQ(p.weights.size(), 10u);
  EXPECT_TRUE(p.targets.empty());
  ASSERT_EQ(s.animation.joint_tracks.size(), 1u);  // joint 1 (node 2) alone is animated
  EXPECT_EQ(s.animation.joint_tracks[0].joint, 1u);
  EXPECT_NE(s.frame_state(0).joints[0], s.frame_state(30).joints[0]);

  const DeformedVertices rest = deformed(s, 0, 0, 0);
  for (size_t v = 0; v < p.positions.size(); ++v)
    expect_near(rest.positions[v], p.positions[v] - glm::vec3(0.5f, 0, 0), 1e-5f);
  // At t = 1 s (frame 30), vertex 9 at (1, 2, 0) follows joint 1 alone: (0.5, 1) about (0, 1) by 90
  // degrees is (-1, 1.5). The file's quaternion (0, 0, 0.707, 0.707) is 1.5e-4 short of unit.
  const DeformedVertices turned = deformed(s, 0, 0, 30);
  ASSERT_EQ(p.weights[9], glm::vec4(0, 1, 0, 0));
  expect_near(turned.positions[9], {-1.0f, 1.5f, 0.0f}, 1e-3f);
  expect_near(turned.positions[0], rest.positions[0], 1e-5f);  // joint 0 alone: it does not move
}

// AnimatedMorphCube: two targets ("thin", "angle") with POSITION, NORMAL and TANGENT deltas; one
// LINEAR weights channel of 127 keys.
TEST_F(GltfSkinsCorpus, AnimatedMorphCubeMorphs) {
  const Scene s = load_gltf_file(kCorpus / "glTF-Sample-Models/AnimatedMorphCube-glTF/AnimatedMorphCube.gltf");
  EXPECT_TRUE(contains(joined(unrendered_features(s)), "morph target TANGENT deltas on 1 mesh"));
  EXPECT_FALSE(contains(joined(unrendered_features(s)), "morph targets on"));
  ASSERT_EQ(s.meshes.size(), 1u);
  EXPECT_EQ(s.meshes[0].weights, std::vector<float>({0.0f, 0.0f}));
  const Primitive& p = s.meshes[0].primitives[0];
  ASSERT_EQ(p.targets.size(), 2u);
  for (const MorphTarget& t : p.targets) {
    EXPECT_EQ(t.positions.size(), p.positions.size());
    EXPECT_EQ(t.normals.size(), p.positions.size());
  }
  EXPECT_EQ(s.instances[0].morph_weights.size(), 2u);
  ASSERT_EQ(s.animation.morph_tracks.size(), 1u);
  EXPECT_EQ(s.animation.morph_tracks[0].keys.size(), 127u);
  const std::vector<float> early = s.frame_state(0).morph_weights[0];
  const std::vector<float> later = s.frame_state(30).morph_weights[0];
  EXPECT_NE(early, later);
  const DeformedVertices a = deformed(s, 0, 0, 0), b = deformed(s, 0, 0, 30);
  EXPECT_NE(a.positions, b.positions);
}

// ---- Skins --------------------------------------------------------------------------------------

TEST(GltfSkins, ReadsSkinJointsAndWeights) {
  const Scene s = load(skinned_quad());
  ASSERT_EQ(s.skins.size(), 1u);
  EXPECT_EQ(s.skins[0].inverse_bind[1], glm::translate(glm::mat4(1.0f), {0, -1, 0}));
  EXPECT_EQ(s.skins[0].joints[0], glm::mat4(1.0f));
  EXPECT_EQ(s.skins[0].joints[1], glm::translate(glm::mat4(1.0f), {0, 1, 0}));
  EXPECT_EQ(s.instances[0].skin, 0);
  EXPECT_TRUE(s.instances[0].deforms());
  const Primitive& p = s.meshes[0].primitives[0];
  EXPECT_EQ(p.joints, std::vector<glm::uvec4>({{0, 0, 0, 0}, {0, 0, 0, 0}, {1, 0, 0, 0}, {1, 0, 0, 0}}));
  EXPECT_EQ(p.weights, std::vector<glm::vec4>(4, glm::vec4(1, 0, 0, 0)));
  // The rest pose is the bind pose.
  const DeformedVertices rest = deformed(s, 0, 0, 0);
  for (size_t v = 0; v < 4; ++v) expect_near(rest.positions[v], p.positions[v], 1e-6f);
}

TEST(GltfSkins, ReadsEveryJointsAndWeightsComponentType) {
  TestGltf g = skinned_quad();
  const std::vector<uint16_t> joints = {0, 1, 0, 0, 1, 0, 0, 0, 1, 1, 0, 0, 0, 0, 0, 0};
  const std::vector<uint8_t> bytes = {255, 0, 0, 0, 128, 127, 0, 0, 0, 255, 0, 0, 51, 204, 0, 0};
  json& attributes = g.doc["meshes"][0]["primitives"][0]["attributes"];
  attributes["JOINTS_0"] = g.accessor(joints.data(), joints.size() * 2, 5123, "VEC4", 4);
  attributes["WEIGHTS_0"] = g.accessor(bytes.data(), bytes.size(), 5121, "VEC4", 4, true);
  Scene s = load(g);
  EXPECT_EQ(s.meshes[0].primitives[0].joints[1], glm::uvec4(1, 0, 0, 0));
  EXPECT_EQ(s.meshes[0].primitives[0].joints[2], glm::uvec4(1, 1, 0, 0));
  EXPECT_EQ(s.meshes[0].primitives[0].weights[1], glm::vec4(128.0f / 255.0f, 127.0f / 255.0f, 0, 0));
  EXPECT_EQ(s.meshes[0].primitives[0].weights[3], glm::vec4(0.2f, 0.8f, 0, 0));
  EXPECT_EQ(joined(s.ignored_features), "");

  const std::vector<uint16_t> shorts = {65535, 0, 0, 0, 32768, 32767, 0, 0, 0, 65535, 0, 0, 65535, 0, 0, 0};
  attributes["WEIGHTS_0"] = g.accessor(shorts.data(), shorts.size() * 2, 5123, "VEC4", 4, true);
  s = load(g);
  EXPECT_EQ(s.meshes[0].primitives[0].weights[1], glm::vec4(32768.0f / 65535.0f, 32767.0f / 65535.0f, 0, 0));
}

// Sums off 1 by more than 1e-3 are divided by the sum, counted per mesh and reported; sums within
// 1e-3 are kept as they are.
TEST(GltfSkins, RenormalisesWeightsOffOneAndSaysSo) {
  TestGltf g = skinned_quad();
  g.doc["meshes"][0]["primitives"][0]["attributes"]["WEIGHTS_0"] =
      g.floats({0.5f, 0, 0, 0, 0.25f, 0.25f, 0, 0, 1.0005f, 0, 0, 0, 0.6f, 0.3f, 0, 0}, "VEC4", 4);
  const Scene s = load(g);
  const std::vector<glm::vec4>& w = s.meshes[0].primitives[0].weights;
  EXPECT_EQ(w[0], glm::vec4(1, 0, 0, 0));
  EXPECT_EQ(w[1], glm::vec4(0.5f, 0.5f, 0, 0));
  EXPECT_EQ(w[2], glm::vec4(1.0005f, 0, 0, 0));
  EXPECT_NEAR(w[3].x, 2.0f / 3.0f, 1e-6f);
  EXPECT_NEAR(w[3].y, 1.0f / 3.0f, 1e-6f);
  EXPECT_TRUE(contains(joined(s.ignored_features),
                       "WEIGHTS_0 renormalised on 3 vertices of mesh 'cloth' (their sums were off 1 by more than 1e-3)\n"));
}

TEST(GltfSkins, MissingInverseBindMatricesAreIdentities) {
  TestGltf g = skinned_quad();
  g.doc["skins"][0].erase("inverseBindMatrices");
  const Scene s = load(g);
  EXPECT_EQ(s.skins[0].inverse_bind, std::vector<glm::mat4>(2, glm::mat4(1.0f)));
}

// Joints need not be nodes of the scene: their transforms are read through their parents anyway.
TEST(GltfSkins, JointsOutsideTheSceneKeepTheirTransforms) {
  TestGltf g = skinned_quad();
  g.doc["scenes"][0]["nodes"] = {0};
  g.doc["nodes"][1]["translation"] = {2, 0, 0};
  const Scene s = load(g);
  EXPECT_EQ(s.skins[0].joints[0], glm::translate(glm::mat4(1.0f), {2, 0, 0}));
  EXPECT_EQ(s.skins[0].joints[1], glm::translate(glm::mat4(1.0f), {2, 1, 0}));
}

// A channel on joint 0 (node 1, a root) is its track as the file has it; joint 1 (node 2, its
// child) is keyed with the composed transform: node 1's turn carries it round.
TEST(GltfSkins, JointChannelsBecomeJointTracksComposedThroughParents) {
  TestGltf g = skinned_quad();
  const float h = std::sqrt(0.5f);
  const int input = g.floats({0.0f, 1.0f}, "SCALAR", 1);
  const int output = g.floats({0, 0, 0, 1, 0, 0, h, h}, "VEC4", 4);
  animate(g, 1, "rotation", input, output);
  const Scene s = load(g);
  ASSERT_EQ(s.animation.joint_tracks.size(), 2u);
  EXPECT_TRUE(s.animation.tracks.empty());  // the skinned node itself does not move
  for (const JointTrack& t : s.animation.joint_tracks) {
    EXPECT_EQ(t.skin, 0u);
    ASSERT_EQ(t.keys.size(), 2u);
  }
  EXPECT_EQ(s.animation.joint_tracks[0].keys[1].rotation, glm::quat(h, 0, 0, h));
  const TransformKey& child = s.animation.joint_tracks[1].keys[1];
  expect_near(child.translation, {-1, 0, 0}, 1e-6f);  // (0, 1, 0) turned 90 degrees about +z
  // At t = 1 s both joints have turned 90 degrees about the origin, and the quad with them.
  const DeformedVertices turned = deformed(s, 0, 0, 30);
  expect_near(turned.positions[3], {-1, 0, 0}, 1e-5f);  // vertex (0, 1, 0)
  expect_near(turned.positions[2], {-1, 1, 0}, 1e-5f);  // vertex (1, 1, 0)
}

TEST(GltfSkins, RefusesBadSkinsByField) {
  struct Case {
    const char* expected;
    void (*breaks)(TestGltf&);
  };
  const Case cases[] = {
      {"meshes[0].primitives[0].attributes.JOINTS_1 is not supported: strata skins with at most 4 joint influences",
       [](TestGltf& g) { g.doc["meshes"][0]["primitives"][0]["attributes"]["JOINTS_1"] = 1; }},
      {"meshes[0].primitives[0].attributes.WEIGHTS_1 is not supported",
       [](TestGltf& g) { g.doc["meshes"][0]["primitives"][0]["attributes"]["WEIGHTS_1"] = 2; }},
      {"meshes[0].primitives[0].attributes.WEIGHTS_0 is missing (JOINTS_0 needs it)",
       [](TestGltf& g) { g.doc["meshes"][0]["primitives"][0]["attributes"].erase("WEIGHTS_0"); }},
      {"meshes[0].primitives[0].attributes.JOINTS_0 (accessors[5]) must be a VEC4 of unsigned byte or unsigned short",
       [](TestGltf& g) {
         g.doc["meshes"][0]["primitives"][0]["attributes"]["JOINTS_0"] = g.floats(std::vector<float>(16, 0.0f), "VEC4", 4);
       }},
      {"meshes[0].primitives[0].attributes.JOINTS_0 has 3 elements, POSITION has 4",
       [](TestGltf& g) {
         const std::vector<uint8_t> j(12, 0);
         g.doc["meshes"][0]["primitives"][0]["attributes"]["JOINTS_0"] = g.accessor(j.data(), j.size(), 5121, "VEC4", 3);
       }},
      {"meshes[0].primitives[0].attributes.WEIGHTS_0 (accessors[5]) element 1 is not finite",
       [](TestGltf& g) {
         g.doc["meshes"][0]["primitives"][0]["attributes"]["WEIGHTS_0"] =
             g.floats({1, 0, 0, 0, kNaN, 0, 0, 0, 1, 0, 0, 0, 1, 0, 0, 0}, "VEC4", 4);
       }},
      {"meshes[0].primitives[0].attributes.WEIGHTS_0 (accessors[5]) element 2 has a negative weight",
       [](TestGltf& g) {
         g.doc["meshes"][0]["primitives"][0]["attributes"]["WEIGHTS_0"] =
             g.floats({1, 0, 0, 0, 1, 0, 0, 0, 1.5f, -0.5f, 0, 0, 1, 0, 0, 0}, "VEC4", 4);
       }},
      {"meshes[0].primitives[0].attributes.WEIGHTS_0 (accessors[5]) element 3 has weights summing to 0",
       [](TestGltf& g) {
         g.doc["meshes"][0]["primitives"][0]["attributes"]["WEIGHTS_0"] =
             g.floats({1, 0, 0, 0, 1, 0, 0, 0, 1, 0, 0, 0, 0, 0, 0, 0}, "VEC4", 4);
       }},
      {"skins[0].joints[1] = 9 is out of range (3 nodes)", [](TestGltf& g) { g.doc["skins"][0]["joints"][1] = 9; }},
      {"skins[0].joints is empty", [](TestGltf& g) { g.doc["skins"][0]["joints"] = json::array(); }},
      {"skins[0].skeleton = 7 is out of range (3 nodes)", [](TestGltf& g) { g.doc["skins"][0]["skeleton"] = 7; }},
      {"skins[0].inverseBindMatrices has 1 matrices, skins[0].joints has 2",
       [](TestGltf& g) {
         const std::vector<float> one = {1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1};
         g.doc["skins"][0]["inverseBindMatrices"] = g.floats(one, "MAT4", 16);
       }},
      {"skins[0].inverseBindMatrices (accessors[5]) matrix 1 is not invertible",
       [](TestGltf& g) {
         const std::vector<float> m = {1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1,  //
                                       1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 0, 0, 0, 0, 0, 1};
         g.doc["skins"][0]["inverseBindMatrices"] = g.floats(m, "MAT4", 16);
       }},
      {"skins[0].inverseBindMatrices (accessors[5]) element 0 is not finite",
       [](TestGltf& g) {
         std::vector<float> m(32, 0.0f);
         m[0] = std::numeric_limits<float>::infinity();
         g.doc["skins"][0]["inverseBindMatrices"] = g.floats(m, "MAT4", 16);
       }},
      {"nodes[0].skin = 3 is out of range (1 skins)", [](TestGltf& g) { g.doc["nodes"][0]["skin"] = 3; }},
      {"meshes[0].primitives[0].attributes.JOINTS_0 is missing (nodes[0] skins meshes[0] with skins[0]",
       [](TestGltf& g) {
         g.doc["meshes"][0]["primitives"][0]["attributes"].erase("JOINTS_0");
         g.doc["meshes"][0]["primitives"][0]["attributes"].erase("WEIGHTS_0");
       }},
      {"meshes[0].primitives[0].attributes.JOINTS_0 element 2 names joint 2, but skins[0] has 2 joints",
       [](TestGltf& g) {
         const std::vector<uint8_t> j = {0, 0, 0, 0, 1, 0, 0, 0, 2, 0, 0, 0, 1, 0, 0, 0};
         g.doc["meshes"][0]["primitives"][0]["attributes"]["JOINTS_0"] = g.accessor(j.data(), j.size(), 5121, "VEC4", 4);
       }},
      {"nodes[0].extensions.MSFT_lod is on a skinned node (a deforming instance has one LoD level)",
       [](TestGltf& g) {
         g.doc["nodes"][0]["extensions"] = {{"MSFT_lod", {{"ids", {3}}}}};
         g.node({{"mesh", g.quad_mesh()}});
       }},
      {"nodes[1] is its own ancestor", [](TestGltf& g) {
         g.doc["nodes"][2]["children"] = {1};
         g.doc["scenes"][0]["nodes"] = {0};
       }},
  };
  ASSERT_EQ(error_of(skinned_quad()), "(loaded without error)");
  for (const Case& c : cases) {
    TestGltf g = skinned_quad();
    c.breaks(g);
    EXPECT_TRUE(contains(error_of(g), std::string("file.glb: ") + c.expected));
  }
}

// ---- Morph targets ------------------------------------------------------------------------------

TEST(GltfMorphTargets, ReadsTargetsAndDefaultWeights) {
  TestGltf g = morph_quad();
  Scene s = load(g);
  const Primitive& p = s.meshes[0].primitives[0];
  ASSERT_EQ(p.targets.size(), 2u);
  EXPECT_EQ(p.targets[0].positions, std::vector<glm::vec3>(4, glm::vec3(0, 0, 1)));
  EXPECT_EQ(p.targets[0].normals, std::vector<glm::vec3>(4, glm::vec3(1, 0, 0)));
  EXPECT_EQ(p.targets[1].positions, std::vector<glm::vec3>(4, glm::vec3(1, 0, 0)));
  EXPECT_TRUE(p.targets[1].normals.empty());
  EXPECT_EQ(s.meshes[0].weights, std::vector<float>({0.25f, 0.5f}));
  EXPECT_EQ(s.instances[0].morph_weights, std::vector<float>({0.25f, 0.5f}));
  EXPECT_EQ(s.instances[0].skin, -1);
  EXPECT_TRUE(s.instances[0].deforms());
  EXPECT_EQ(joined(s.ignored_features), "");
  const DeformedVertices v = deformed(s, 0, 0, 0);
  expect_near(v.positions[2], glm::vec3(1, 1, 0) + glm::vec3(0.5f, 0, 0.25f), 1e-6f);
  expect_near(v.normals[0], glm::normalize(glm::vec3(0.25f, 0, 1)), 1e-6f);

  g.doc["nodes"][0]["weights"] = {1.0, 0.0};  // the node's weights win over the mesh's
  EXPECT_EQ(load(g).instances[0].morph_weights, std::vector<float>({1.0f, 0.0f}));
  g.doc["meshes"][0].erase("weights");
  g.doc["nodes"][0].erase("weights");
  EXPECT_EQ(load(g).meshes[0].weights, std::vector<float>({0.0f, 0.0f}));  // default: zeros
}

// A mesh without normals gets them from its rest pose; the targets' NORMAL deltas move those.
TEST(GltfMorphTargets, GeneratedNormalsComeFromTheRestPose) {
  TestGltf g = morph_quad();
  g.doc["meshes"][0]["primitives"][0]["attributes"].erase("NORMAL");
  const Scene s = load(g);
  EXPECT_EQ(s.meshes[0].primitives[0].normals, std::vector<glm::vec3>(4, glm::vec3(0, 0, 1)));
  EXPECT_EQ(s.meshes[0].primitives[0].targets[0].normals, std::vector<glm::vec3>(4, glm::vec3(1, 0, 0)));
}

TEST(GltfMorphTargets, LinearWeightsChannelsAreCopiedAndStepChannelsHold) {
  TestGltf g = morph_quad();
  const int input = g.floats({0.0f, 1.0f, 2.0f}, "SCALAR", 1);
  const int output = g.floats({0, 0, 1, 0, 0, 1}, "SCALAR", 1);
  animate(g, 0, "weights", input, output);
  Scene s = load(g);
  ASSERT_EQ(s.animation.morph_tracks.size(), 1u);
  EXPECT_EQ(s.animation.morph_tracks[0].instance, 0u);
  const std::vector<MorphKey> linear = {{0.0f, {0, 0}}, {1.0f, {1, 0}}, {2.0f, {0, 1}}};
  EXPECT_EQ(s.animation.morph_tracks[0].keys, linear);
  EXPECT_EQ(s.frame_state(15).morph_weights[0], std::vector<float>({0.5f, 0.0f}));

  g.doc["animations"][0]["samplers"][0]["interpolation"] = "STEP";
  s = load(g);
  const std::vector<MorphKey>& step = s.animation.morph_tracks[0].keys;
  ASSERT_EQ(step.size(), 5u);
  EXPECT_EQ(step[1].weights, std::vector<float>({0, 0}));
  EXPECT_EQ(step[1].time, std::nextafter(1.0f, 0.0f));
  EXPECT_EQ(s.frame_state(15).morph_weights[0], std::vector<float>({0.0f, 0.0f}));
  EXPECT_EQ(s.frame_state(45).morph_weights[0], std::vector<float>({1.0f, 0.0f}));
}

TEST(GltfMorphTargets, RefusesBadTargetsByField) {
  struct Case {
    const char* expected;
    void (*breaks)(TestGltf&);
  };
  const Case cases[] = {
      {"meshes[0].primitives[0].targets[1].POSITION has 3 elements, POSITION has 4",
       [](TestGltf& g) {
         g.doc["meshes"][0]["primitives"][0]["targets"][1]["POSITION"] = g.floats(std::vector<float>(9, 0.0f), "VEC3", 3);
       }},
      {"meshes[0].primitives[0].targets[0].NORMAL has 5 elements, POSITION has 4",
       [](TestGltf& g) {
         g.doc["meshes"][0]["primitives"][0]["targets"][0]["NORMAL"] = g.floats(std::vector<float>(15, 0.0f), "VEC3", 3);
       }},
      {"meshes[0].primitives[1].targets has 1 morph targets, primitives[0] has 2",
       [](TestGltf& g) {
         json second = g.doc["meshes"][0]["primitives"][0];
         second["targets"].erase(1);
         g.doc["meshes"][0]["primitives"].push_back(second);
       }},
      {"meshes[0].weights has 3 entries, the mesh has 2 morph targets",
       [](TestGltf& g) { g.doc["meshes"][0]["weights"] = {0.0, 0.0, 0.0}; }},
      {"nodes[0].weights has 1 entries, meshes[0] has 2 morph targets",
       [](TestGltf& g) { g.doc["nodes"][0]["weights"] = {0.5}; }},
      {"nodes[0].extensions.MSFT_lod is on a morphing node (a deforming instance has one LoD level)",
       [](TestGltf& g) {
         g.doc["nodes"][0]["extensions"] = {{"MSFT_lod", {{"ids", {1}}}}};
         g.node({{"mesh", g.quad_mesh()}});
       }},
      {"animations[0].samplers[0].output has 5 elements, not input's 3 keys x 2 morph targets of nodes[0]'s mesh",
       [](TestGltf& g) {
         animate(g, 0, "weights", g.floats({0, 1, 2}, "SCALAR", 1), g.floats({0, 0, 1, 0, 0}, "SCALAR", 1));
       }},
      {"animations[0].samplers[0].interpolation = CUBICSPLINE is not supported (LINEAR or STEP)",
       [](TestGltf& g) {
         animate(g, 0, "weights", g.floats({0}, "SCALAR", 1), g.floats({0, 0, 0, 0, 0, 0}, "SCALAR", 1), "CUBICSPLINE");
       }},
      {"animations[0].channels[0].target.path = weights, but nodes[1] has no mesh with morph targets",
       [](TestGltf& g) {
         g.node({{"mesh", g.quad_mesh()}});
         animate(g, 1, "weights", g.floats({0}, "SCALAR", 1), g.floats({0}, "SCALAR", 1));
       }},
  };
  ASSERT_EQ(error_of(morph_quad()), "(loaded without error)");
  for (const Case& c : cases) {
    TestGltf g = morph_quad();
    c.breaks(g);
    EXPECT_TRUE(contains(error_of(g), std::string("file.glb: ") + c.expected));
  }
}

// Targets may share one accessor, so a small file could ask for vertices x targets without end.
TEST(GltfMorphTargets, RefusesMoreTargetVerticesThanTheLimit) {
  TestGltf g;
  const size_t vertices = 1'000'002;  // a multiple of 3: a triangle list without indices
  const int positions = g.floats(std::vector<float>(3 * vertices, 0.0f), "VEC3", 3);
  const json target = {{"POSITION", positions}};
  const size_t targets = kMaxMorphTargetVerticesForTest / vertices + 1;
  g.mesh({{"attributes", {{"POSITION", positions}}}, {"targets", json::array()}});
  for (size_t t = 0; t < targets; ++t) g.doc["meshes"][0]["primitives"][0]["targets"].push_back(target);
  g.node({{"mesh", 0}});
  EXPECT_TRUE(contains(error_of(g), "file.glb: meshes[0].primitives[0].targets bring the morph target vertex count "
                                    "(vertices x targets) to 16000032, over the limit of 16000000"));
}

// ---- Scene::validate ----------------------------------------------------------------------------

TEST(SkinAndMorphValidation, RefusesInconsistentDeformationData) {
  const Scene skinned = load(skinned_quad());
  const Scene morphing = load(morph_quad());
  ASSERT_EQ(validate_error(skinned), "(valid)");
  ASSERT_EQ(validate_error(morphing), "(valid)");
  struct Case {
    const Scene* base;
    const char* expected;
    void (*breaks)(Scene&);
  };
  const Case cases[] = {
      {&skinned, "meshes[0].primitives[0].weights has 3 entries, not one per vertex (4)",
       [](Scene& s) { s.meshes[0].primitives[0].weights.pop_back(); }},
      {&skinned, "meshes[0].primitives[0].weights[1] is not finite",
       [](Scene& s) { s.meshes[0].primitives[0].weights[1].y = kNaN; }},
      {&skinned, "meshes[0].primitives[0].joints[2] names joint 5, but instances[0]'s skin, skins[0], has 2 joints",
       [](Scene& s) { s.meshes[0].primitives[0].joints[2].z = 5; }},
      {&skinned, "meshes[0].primitives[0].joints is empty, but instances[0] skins the mesh",
       [](Scene& s) {
         s.meshes[0].primitives[0].joints.clear();
         s.meshes[0].primitives[0].weights.clear();
       }},
      {&skinned, "instances[0].skin = 1 is neither -1 nor a skin (1 skins)", [](Scene& s) { s.instances[0].skin = 1; }},
      {&skinned, "skins[0].inverse_bind[1][3] is not finite", [](Scene& s) { s.skins[0].inverse_bind[1][3][1] = kNaN; }},
      {&skinned, "skins[0].joints[0][0] is not finite", [](Scene& s) { s.skins[0].joints[0][0][0] = kNaN; }},
      {&skinned, "skins[0].inverse_bind has 1 entries, not one per joint (2)",
       [](Scene& s) { s.skins[0].inverse_bind.pop_back(); }},
      {&skinned, "animation.joint_tracks[0].joint = 7 is out of range (2 joints)",
       [](Scene& s) { s.animation.joint_tracks.push_back(JointTrack{0, 7, {TransformKey{}}}); }},
      {&skinned, "animation.joint_tracks[0].skin = 2 is out of range (1 skins)",
       [](Scene& s) { s.animation.joint_tracks.push_back(JointTrack{2, 0, {TransformKey{}}}); }},
      {&skinned, "instances[0].lod_meshes has 2 LoD levels; a deforming instance has one",
       [](Scene& s) { s.instances[0].lod_meshes.push_back(0); }},
      {&morphing, "meshes[0].primitives[0].targets[1].positions has 3 entries, not one per vertex (4)",
       [](Scene& s) { s.meshes[0].primitives[0].targets[1].positions.pop_back(); }},
      {&morphing, "meshes[0].primitives[0].targets has 2 entries, not one per weight of the mesh (3)",
       [](Scene& s) { s.meshes[0].weights.push_back(0.0f); }},
      {&morphing, "instances[0].morph_weights has 1 entries, not one per morph target of meshes[0] (2)",
       [](Scene& s) { s.instances[0].morph_weights.pop_back(); }},
      {&morphing, "animation.morph_tracks[0].keys[1].weights has 3 entries, not one per morph target (2)",
       [](Scene& s) { s.animation.morph_tracks.push_back(MorphTrack{0, {{0.0f, {0, 0}}, {1.0f, {0, 0, 0}}}}); }},
      {&morphing, "animation.morph_tracks[0].instance = 3 is out of range (1 instances)",
       [](Scene& s) { s.animation.morph_tracks.push_back(MorphTrack{3, {{0.0f, {0, 0}}}}); }},
      {&skinned, "animation.morph_tracks[0].instance = 0 has no morph targets",
       [](Scene& s) { s.animation.morph_tracks.push_back(MorphTrack{0, {{0.0f, {}}}}); }},
  };
  for (const Case& c : cases) {
    Scene s = *c.base;
    c.breaks(s);
    EXPECT_TRUE(contains(validate_error(s), c.expected));
  }
}

}  // namespace
}  // namespace strata::scene
