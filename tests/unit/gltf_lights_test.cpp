// KHR_lights_punctual into Scene::lights: types, units and cones as the extension defines them,
// attached to nodes (world transform at rest, node animation as a LightTrack), bad values refused
// naming the field and the value.
#include <cmath>
#include <functional>

#include <gtest/gtest.h>

#include "gltf_test_builder.h"
#include "scene/scene_io.h"

namespace strata::scene {
namespace {

using nlohmann::json;
using testing::TestGltf;

TestGltf lit_quad() {
  TestGltf g;
  g.node({{"mesh", g.quad_mesh()}});
  g.doc["extensionsUsed"] = {"KHR_lights_punctual"};
  g.doc["extensions"]["KHR_lights_punctual"]["lights"] = json::array(
      {{{"type", "point"}, {"color", {1.0, 0.5, 0.25}}, {"intensity", 40.0}, {"range", 10.0}},
       {{"type", "spot"}, {"intensity", 5.0}, {"spot", {{"innerConeAngle", 0.2}, {"outerConeAngle", 0.6}}}},
       {{"type", "directional"}, {"intensity", 3.0}}});
  // Node 1 (child of node 2, which sits at x = 2) carries the point light; node 3 the spot and
  // node 4 the directional light.
  g.node({{"translation", {0.0, 1.0, 0.0}}, {"extensions", {{"KHR_lights_punctual", {{"light", 0}}}}}});
  g.node({{"translation", {2.0, 0.0, 0.0}}, {"children", {1}}});
  g.node({{"extensions", {{"KHR_lights_punctual", {{"light", 1}}}}}});
  g.node({{"extensions", {{"KHR_lights_punctual", {{"light", 2}}}}}});
  g.scene({0, 2, 3, 4});
  return g;
}

std::string error_of(const TestGltf& g) {
  try {
    load_glb_bytes(g.glb(), "l.glb");
  } catch (const SceneError& e) {
    return e.what();
  }
  return "(loaded without error)";
}

TEST(GltfLights, PointSpotAndDirectionalLightsFollowTheirNodes) {
  const Scene s = load_glb_bytes(lit_quad().glb(), "l.glb");
  ASSERT_EQ(s.lights.size(), 3u);
  const Light& point = s.lights[0];
  EXPECT_EQ(point.type, LightType::kPoint);
  EXPECT_EQ(point.color, glm::vec3(1.0f, 0.5f, 0.25f));
  EXPECT_FLOAT_EQ(point.intensity, 40.0f);
  EXPECT_FLOAT_EQ(point.range, 10.0f);
  EXPECT_EQ(glm::vec3(point.transform[3]), glm::vec3(2.0f, 1.0f, 0.0f));  // parent x child
  EXPECT_EQ(s.lights[1].type, LightType::kSpot);
  EXPECT_FLOAT_EQ(s.lights[1].inner_cone, 0.2f);
  EXPECT_FLOAT_EQ(s.lights[1].outer_cone, 0.6f);
  EXPECT_EQ(s.lights[2].type, LightType::kDirectional);
  EXPECT_EQ(s.frame_state(0).lights.size(), 3u);
}

TEST(GltfLights, NodeAnimationMovesTheLight) {
  TestGltf g = lit_quad();
  const int times = g.floats({0.0f, 1.0f}, "SCALAR", 1);
  const int values = g.floats({2, 0, 0, 6, 0, 0}, "VEC3", 3);
  g.doc["animations"] = json::array(
      {{{"samplers", json::array({{{"input", times}, {"output", values}}})},
        {"channels", json::array({{{"sampler", 0}, {"target", {{"node", 2}, {"path", "translation"}}}}})}}});
  const Scene s = load_glb_bytes(g.glb(), "l.glb");
  ASSERT_EQ(s.animation.light_tracks.size(), 1u);
  EXPECT_EQ(s.animation.light_tracks[0].light, 0u);
  const FrameState end = s.frame_state(uint32_t(s.animation.frames_per_second));  // t = 1 s
  EXPECT_NEAR(end.lights[0][3].x, 6.0f, 1e-5f);
  EXPECT_NEAR(end.lights[0][3].y, 1.0f, 1e-5f);
}

TEST(GltfLights, BadValuesAreRefusedNamingTheField) {
  TestGltf g = lit_quad();
  g.doc["extensions"]["KHR_lights_punctual"]["lights"][1]["spot"]["innerConeAngle"] = 0.7;
  EXPECT_NE(error_of(g).find("l.glb: extensions.KHR_lights_punctual.lights[1].spot.innerConeAngle = 0.7 is not "
                             "below outerConeAngle (0.6)"),
            std::string::npos)
      << error_of(g);
  g = lit_quad();
  g.doc["extensions"]["KHR_lights_punctual"]["lights"][0]["intensity"] = 1e300;
  EXPECT_NE(error_of(g).find("lights[0].intensity = 1e+300 is not a finite number"), std::string::npos)
      << error_of(g);
  g = lit_quad();
  g.doc["extensions"]["KHR_lights_punctual"]["lights"][1]["spot"]["outerConeAngle"] = 2.0;
  EXPECT_NE(error_of(g).find("lights[1].spot.outerConeAngle = 2 is outside [0, 1.5708]"), std::string::npos)
      << error_of(g);
  g = lit_quad();
  g.doc["extensions"]["KHR_lights_punctual"]["lights"][0]["type"] = "area";
  EXPECT_NE(error_of(g).find("lights[0].type = 'area' is not directional, point or spot"), std::string::npos);
  g = lit_quad();
  g.doc["nodes"][3]["extensions"]["KHR_lights_punctual"]["light"] = 9;
  EXPECT_NE(error_of(g).find("nodes[3].extensions.KHR_lights_punctual.light = 9 is out of range (3 lights)"),
            std::string::npos)
      << error_of(g);
}

// Scene::validate (built-in scenes, and every loader before it returns) refuses the values the
// device could not evaluate: a non-finite intensity, a spot whose cones meet or cross.
TEST(GltfLights, SceneValidateRefusesNonFiniteAndCrossedCones) {
  const Scene lit = load_glb_bytes(lit_quad().glb(), "l.glb");
  auto error = [&](const std::function<void(Scene&)>& edit) -> std::string {
    Scene s = lit;
    edit(s);
    try {
      s.validate();
    } catch (const SceneError& e) {
      return e.what();
    }
    return "(valid)";
  };
  EXPECT_NE(error([](Scene& s) { s.lights[0].intensity = std::nanf(""); }).find("lights[0].intensity"), std::string::npos);
  EXPECT_NE(error([](Scene& s) { s.lights[0].intensity = INFINITY; }).find("lights[0].intensity"), std::string::npos);
  EXPECT_NE(error([](Scene& s) { s.lights[0].color.g = std::nanf(""); }).find("lights[0].color"), std::string::npos);
  EXPECT_NE(error([](Scene& s) { s.lights[0].range = -1.0f; }).find("lights[0].range"), std::string::npos);
  EXPECT_NE(error([](Scene& s) { s.lights[1].inner_cone = s.lights[1].outer_cone; }).find("lights[1].inner_cone"),
            std::string::npos);
  EXPECT_NE(error([](Scene& s) { s.lights[1].outer_cone = std::nanf(""); }).find("lights[1].outer_cone"), std::string::npos);
  EXPECT_EQ(error([](Scene&) {}), "(valid)");
}

}  // namespace
}  // namespace strata::scene
