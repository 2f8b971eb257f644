// The built-in scenes lit the hard way: night-street (many lights, most of the power far from what
// the camera sees, lights that move with their objects) and atrium (a closed room lit only through
// holes in its shell).
#include <algorithm>
#include <cmath>
#include <random>
#include <string>

#include <gtest/gtest.h>

#include "render/light_sampler_choice.h"
#include "render/punctual_lights.h"
#include "scene/scene_io.h"
#include "support/cpu_tracer.h"

namespace strata::scene {
namespace {

size_t emissive_triangles(const Scene& s) {
  size_t n = 0;
  for (const Mesh& m : s.meshes)
    for (const Primitive& p : m.primitives)
      if (glm::any(glm::greaterThan(s.materials[p.material].emission, glm::vec3(0.0f)))) n += p.triangle_count();
  return n;
}

size_t instance_named(const Scene& s, const std::string& name) {
  for (size_t i = 0; i < s.instances.size(); ++i)
    if (s.instances[i].name == name) return i;
  throw std::runtime_error("no instance " + name);
}

bool alpha_masked_double_sided(const Scene& s) {
  return std::any_of(s.materials.begin(), s.materials.end(), [](const Material& m) {
    return m.alpha_mode == AlphaMode::kMask && m.double_sided && m.base_color_texture.texture >= 0;
  });
}

TEST(BuiltinNightStreet, ManyLightsMostPowerFarAway) {
  const Scene s = builtin_scene("night-street");
  EXPECT_GE(emissive_triangles(s), 500u);
  EXPECT_LE(s.triangle_count(), 4'000u);
  ASSERT_EQ(s.lights.size(), 64u);
  EXPECT_TRUE(alpha_masked_double_sided(s));
  ASSERT_TRUE(s.environment.map.has_value());
  for (const glm::vec3& texel : s.environment.map->radiance) EXPECT_LT(std::max({texel.r, texel.g, texel.b}), 0.05f);
  // The floodlights and high masts at the far end hold most of the punctual power.
  const double radius = render::scene_bounding_radius(s);
  double far = 0.0, total = 0.0;
  for (const Light& l : s.lights) {
    const double power = render::punctual_power(l, radius);
    total += power;
    if (l.name.starts_with("floodlight") || l.name.starts_with("high mast")) far += power;
  }
  EXPECT_GT(far, 0.5 * total);
}

// light_sampler auto takes the tree on night-street and power where a few lights light the scene.
TEST(BuiltinNightStreet, AutoLightSamplerTakesTheTreeForItsManyLights) {
  using render::LightSampler;
  EXPECT_EQ(render::bounded_lights(builtin_scene("night-street")), 822u);  // 758 emissive triangles, 64 point and spot lights
  EXPECT_EQ(render::bounded_lights(builtin_scene("cornell")), 2u);
  EXPECT_EQ(render::bounded_lights(builtin_scene("cornell-lamps")), 2u);   // its sun is directional
  EXPECT_EQ(render::light_sampler_in_use(LightSampler::automatic, 822), LightSampler::tree);
  EXPECT_EQ(render::light_sampler_in_use(LightSampler::automatic, render::k_auto_light_tree_min_lights), LightSampler::tree);
  EXPECT_EQ(render::light_sampler_in_use(LightSampler::automatic, render::k_auto_light_tree_min_lights - 1), LightSampler::power);
  EXPECT_EQ(render::light_sampler_in_use(LightSampler::power, 822), LightSampler::power);
  EXPECT_EQ(render::light_sampler_in_use(LightSampler::tree, 2), LightSampler::tree);
}

TEST(BuiltinNightStreet, CameraCarsAndLanternsMoveWithinSixteenFrames) {
  const Scene s = builtin_scene("night-street");
  const FrameState first = s.frame_state(0), later = s.frame_state(15);
  EXPECT_GT(glm::length(later.camera.position - first.camera.position), 0.5f);
  for (const char* car : {"car away", "car towards"}) {
    const size_t i = instance_named(s, car);
    EXPECT_GT(glm::length(glm::vec3(later.transforms[i][3] - first.transforms[i][3])), 4.0f) << car;
  }
  // 12 lanterns and 2 cars x 4 lamps move; every moving light moves within the 16 frames.
  ASSERT_EQ(s.animation.light_tracks.size(), 20u);
  for (const LightTrack& t : s.animation.light_tracks)
    EXPECT_GT(glm::length(glm::vec3(later.lights[t.light][3] - first.lights[t.light][3])), 0.01f) << s.lights[t.light].name;
  // A car's lamps ride on it: their pose in the car's frame is the same in every frame.
  const size_t car = instance_named(s, "car towards");
  for (size_t l = 0; l < s.lights.size(); ++l) {
    if (!s.lights[l].name.starts_with("car towards")) continue;
    const FrameState end = s.frame_state(119);
    const glm::mat4 a = glm::inverse(first.transforms[car]) * first.lights[l];
    const glm::mat4 b = glm::inverse(end.transforms[car]) * end.lights[l];
    for (int c = 0; c < 4; ++c)
      for (int r = 0; r < 4; ++r) EXPECT_NEAR(a[c][r], b[c][r], 1e-4f) << s.lights[l].name;
  }
}

// Where a ray from inside leaves the room's box [-5, 5] x [0, 5] x [-7, 7] (it starts inside).
glm::dvec3 box_exit(const glm::dvec3& o, const glm::dvec3& d) {
  double t = 1e30;
  const glm::dvec3 lo(-5.0, 0.0, -7.0), hi(5.0, 5.0, 7.0);
  for (int a = 0; a < 3; ++a) {
    if (d[a] > 0.0) t = std::min(t, (hi[a] - o[a]) / d[a]);
    if (d[a] < 0.0) t = std::min(t, (lo[a] - o[a]) / d[a]);
  }
  return o + t * d;
}

// The openings atrium.cpp cuts: three windows in the left wall, a clerestory in the back wall and
// the skylight (a small margin for rays through the reveals' edges).
bool in_an_opening(const glm::dvec3& p) {
  const double e = 1e-3;
  if (std::abs(p.x + 5.0) < e && p.y > 0.8 - e && p.y < 3.6 + e)
    for (const double z : {4.0, 0.0, -4.0})
      if (std::abs(p.z - z) < 0.7 + e) return true;
  if (std::abs(p.z + 7.0) < e && std::abs(p.x) < 3.0 + e && p.y > 3.6 - e && p.y < 4.5 + e) return true;
  return std::abs(p.y - 5.0) < e && std::abs(p.x) < 1.5 + e && std::abs(p.z) < 2.0 + e;
}

TEST(BuiltinAtrium, ClosedRoomLitOnlyBySunAndSkyThroughItsOpenings) {
  const Scene s = builtin_scene("atrium");
  EXPECT_EQ(emissive_triangles(s), 0u);
  ASSERT_EQ(s.lights.size(), 1u);
  EXPECT_EQ(s.lights[0].type, LightType::kDirectional);
  EXPECT_TRUE(s.environment.map.has_value());
  EXPECT_TRUE(alpha_masked_double_sided(s));
  EXPECT_LE(s.triangle_count(), 2'000u);
  const FrameState first = s.frame_state(0), later = s.frame_state(15);
  EXPECT_NE(first.camera.position, later.camera.position);
  EXPECT_NE(first.transforms, later.transforms);

  // Rays from inside escape only through the openings, and some do.
  const test::CpuScene cpu = test::build_cpu_scene(s, first);
  std::mt19937 rng(7);
  std::normal_distribution<double> normal;
  size_t escaped = 0;
  for (const glm::dvec3 origin : {glm::dvec3(0.0, 1.0, 0.0), glm::dvec3(-3.5, 2.0, 3.0), glm::dvec3(2.0, 4.0, -5.5)}) {
    for (int k = 0; k < 2000; ++k) {
      test::CpuRay ray;
      ray.origin = origin;
      ray.direction = glm::normalize(glm::dvec3(normal(rng), normal(rng), normal(rng)));
      if (test::intersect(cpu, ray)) continue;
      ++escaped;
      const glm::dvec3 exit = box_exit(origin, ray.direction);
      EXPECT_TRUE(in_an_opening(exit)) << "escaped at " << exit.x << ", " << exit.y << ", " << exit.z;
    }
  }
  EXPECT_GT(escaped, 50u);
  // The sun reaches the floor through the front window (a light shines down its local -Z).
  const glm::dvec3 to_sun = glm::dvec3(glm::normalize(glm::vec3(first.lights[0][2])));
  test::CpuRay sunward;
  sunward.origin = glm::dvec3(-5.0, 2.2, 4.0) - to_sun * (2.2 / to_sun.y) + glm::dvec3(0.0, 1e-3, 0.0);
  sunward.direction = to_sun;
  EXPECT_FALSE(test::intersect(cpu, sunward).has_value());
}

}  // namespace
}  // namespace strata::scene
