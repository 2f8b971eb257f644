// Built-in procedural scenes: valid, deterministic, lit, within budget, with the documented
// LoD levels and a 120-frame animation.
#include <algorithm>
#include <cmath>
#include <map>
#include <string>

#include <gtest/gtest.h>

#include "scene/animation.h"
#include "scene/scene_io.h"

namespace strata::scene {
namespace {

class BuiltinScene : public ::testing::TestWithParam<std::string> {};

// Each scene built once for the read-only tests (lod-cliff and chess take a while in Debug).
const Scene& cached(const std::string& name) {
  static std::map<std::string, Scene> scenes;
  auto it = scenes.find(name);
  if (it == scenes.end()) it = scenes.emplace(name, builtin_scene(name)).first;
  return it->second;
}

bool has_emitter(const Scene& s) {
  return std::any_of(s.materials.begin(), s.materials.end(), [](const Material& m) {
    return glm::any(glm::greaterThan(m.emission, glm::vec3(0.0f)));
  });
}

const Instance& instance_named(const Scene& s, const std::string& name) {
  for (const Instance& i : s.instances) {
    if (i.name == name) return i;
  }
  throw std::runtime_error("no instance " + name);
}

size_t mesh_triangles(const Scene& s, uint32_t mesh) {
  size_t n = 0;
  for (const Primitive& p : s.meshes[mesh].primitives) n += p.triangle_count();
  return n;
}

TEST_P(BuiltinScene, ValidatesAndBuildsTheSameTwice) {
  const Scene a = builtin_scene(GetParam());
  EXPECT_NO_THROW(a.validate());
  EXPECT_EQ(a, builtin_scene(GetParam()));
  EXPECT_EQ(a.name, GetParam());
}

TEST_P(BuiltinScene, IsNonEmptyLitAndWithinBudget) {
  const Scene& s = cached(GetParam());
  EXPECT_FALSE(s.instances.empty());
  EXPECT_GT(s.triangle_count(), 0u);
  EXPECT_LE(s.triangle_count(), 150'000u);
  EXPECT_TRUE(has_emitter(s) || !s.lights.empty());  // emissive triangles or punctual lights
}

TEST_P(BuiltinScene, Animates120FramesAt30Fps) {
  const Scene& s = cached(GetParam());
  EXPECT_EQ(s.animation.frames_per_second, 30.0f);
  EXPECT_EQ(animation_duration(s.animation), frame_time(119, 30.0f));
  EXPECT_EQ(s.animation.camera.front().position, s.camera.position);
  // Frame 0 shows the scene as its fields hold it.
  const FrameState first = s.frame_state(0);
  for (size_t i = 0; i < s.instances.size(); ++i) {
    EXPECT_EQ(first.transforms[i], s.instances[i].transform) << s.instances[i].name;
    EXPECT_EQ(first.lods[i], s.instances[i].lod) << s.instances[i].name;
  }
}

// Triangles wind counter-clockwise around their vertex normals (front faces face outwards).
// Simplified LoD levels keep the fine level's vertex normals (fine shading on coarse geometry),
// so a big triangle across the cliff can lean more than 90 degrees away from them; there up to
// 5% may disagree (a winding mistake would make nearly all of them disagree).
TEST_P(BuiltinScene, WindingAgreesWithNormals) {
  const Scene& s = cached(GetParam());
  std::vector<bool> coarse(s.meshes.size(), false);
  for (const Instance& i : s.instances) {
    for (size_t l = 1; l < i.lod_meshes.size(); ++l) coarse[i.lod_meshes[l]] = true;
  }
  for (size_t m = 0; m < s.meshes.size(); ++m) {
    for (const Primitive& p : s.meshes[m].primitives) {
      size_t disagree = 0;
      for (size_t t = 0; t < p.indices.size(); t += 3) {
        const glm::vec3 a = p.positions[p.indices[t]], b = p.positions[p.indices[t + 1]],
                        c = p.positions[p.indices[t + 2]];
        const glm::vec3 face = glm::cross(b - a, c - a);
        const float longest = std::max({glm::length(b - a), glm::length(c - b), glm::length(a - c)});
        if (glm::length(face) <= 1e-3f * longest * longest) continue;  // sliver: no clear facing
        const glm::vec3 n = p.normals[p.indices[t]] + p.normals[p.indices[t + 1]] +
                            p.normals[p.indices[t + 2]];
        if (glm::dot(face, n) <= 0.0f) ++disagree;
      }
      const size_t allowed = coarse[m] ? p.triangle_count() / 20 : 0;
      EXPECT_LE(disagree, allowed) << s.meshes[m].name;
    }
  }
}

// gtest names may not contain '-'.
std::string param_name(const ::testing::TestParamInfo<std::string>& param) {
  std::string name = param.param;
  std::replace(name.begin(), name.end(), '-', '_');
  return name;
}

INSTANTIATE_TEST_SUITE_P(Builtin, BuiltinScene, ::testing::ValuesIn(builtin_scene_names()), param_name);

TEST(BuiltinRegistry, NamesCornellFirstAndRejectsUnknownNames) {
  const std::vector<std::string> names = builtin_scene_names();
  EXPECT_EQ(names, (std::vector<std::string>{"cornell", "cornell-lamps", "carousel", "carousel-bounce", "lod-cliff", "chess",
                                             "foliage", "overlap-uv", "stiff", "lod-bounce", "courtyard", "night-street", "atrium",
                                             "characters"}));
  EXPECT_TRUE(is_builtin_scene("chess"));
  EXPECT_FALSE(is_builtin_scene("Chess"));
  try {
    builtin_scene("nope");
    FAIL() << "no SceneError";
  } catch (const SceneError& e) {
    EXPECT_NE(std::string(e.what()).find("unknown built-in scene 'nope'"), std::string::npos);
  }
  EXPECT_EQ(load_scene("cornell"), builtin_scene("cornell"));
}

TEST(BuiltinCornell, IsMatteClosedBoxWithADownwardLight) {
  const Scene& s = cached("cornell");
  for (const Material& m : s.materials) {
    EXPECT_EQ(m.metallic, 0.0f) << m.name;
    EXPECT_EQ(m.roughness, 1.0f) << m.name;
  }
  const Instance& light = instance_named(s, "light");
  const Primitive& quad = s.meshes[light.lod_meshes[0]].primitives[0];
  EXPECT_EQ(s.materials[quad.material].emission, glm::vec3(17.0f, 12.0f, 4.0f));
  EXPECT_EQ(quad.normals[0], glm::vec3(0.0f, -1.0f, 0.0f));
  EXPECT_EQ(s.environment.radiance, glm::vec3(0.0f));
  EXPECT_EQ(s.frame_state(0).camera, s.frame_state(119).camera);
  EXPECT_TRUE(s.animation.tracks.empty());
}

TEST(BuiltinLodCliff, HasThreeShrinkingLevelsSwitchedAsTheCameraApproaches) {
  const Scene& s = cached("lod-cliff");
  const Instance& terrain = instance_named(s, "terrain");
  ASSERT_EQ(terrain.lod_meshes.size(), 3u);
  const size_t l0 = mesh_triangles(s, terrain.lod_meshes[0]);
  const size_t l1 = mesh_triangles(s, terrain.lod_meshes[1]);
  const size_t l2 = mesh_triangles(s, terrain.lod_meshes[2]);
  EXPECT_EQ(l0, 159u * 159u * 2u);
  EXPECT_NEAR(static_cast<double>(l1) / static_cast<double>(l0), 0.25, 0.03);
  EXPECT_NEAR(static_cast<double>(l2) / static_cast<double>(l0), 1.0 / 16.0, 0.02);
  EXPECT_EQ(s.frame_state(0).lods[0], 2u);
  EXPECT_EQ(s.frame_state(40).lods[0], 1u);
  EXPECT_EQ(s.frame_state(119).lods[0], 0u);
  EXPECT_GT(s.environment.radiance.b, 0.0f);
}

TEST(BuiltinChess, PiecesHaveThreeLevelsAndTheRookSwitchesEveryTenFrames) {
  const Scene& s = cached("chess");
  for (const char* piece : {"pawn", "queen", "rook"}) {
    const Instance& i = instance_named(s, piece);
    ASSERT_EQ(i.lod_meshes.size(), 3u) << piece;
    const size_t l0 = mesh_triangles(s, i.lod_meshes[0]);
    EXPECT_GE(l0, 8'000u) << piece;
    EXPECT_LE(l0, 15'000u) << piece;
    EXPECT_GT(l0, mesh_triangles(s, i.lod_meshes[1])) << piece;
    EXPECT_GT(mesh_triangles(s, i.lod_meshes[1]), mesh_triangles(s, i.lod_meshes[2])) << piece;
  }
  const auto rook = static_cast<size_t>(&instance_named(s, "rook") - s.instances.data());
  for (uint32_t f = 10; f < 120; f += 10)
    EXPECT_NE(s.frame_state(f).lods[rook], s.frame_state(f - 1).lods[rook]) << f;
}

TEST(BuiltinOverlapUv, UvSquaresAreSharedAndLevelsAlternate) {
  const Scene& s = cached("overlap-uv");
  const Instance& cube = instance_named(s, "cube");
  ASSERT_EQ(cube.lod_meshes.size(), 2u);
  const Primitive& faces = s.meshes[cube.lod_meshes[0]].primitives[0];
  // Every face covers the whole UV square: 6 vertices sit at uv (0, 0) and 6 at (1, 1).
  EXPECT_EQ(std::count(faces.uvs.begin(), faces.uvs.end(), glm::vec2(0.0f)), 6);
  EXPECT_EQ(std::count(faces.uvs.begin(), faces.uvs.end(), glm::vec2(1.0f)), 6);
  const Instance& floor = instance_named(s, "floor");
  ASSERT_EQ(floor.lod_meshes.size(), 2u);
  const Primitive& plane = s.meshes[floor.lod_meshes[0]].primitives[0];
  for (size_t v = 0; v < plane.positions.size(); ++v)
    EXPECT_FLOAT_EQ(plane.uvs[v].x, std::abs(plane.positions[v].x) / 2.0f);
  EXPECT_NE(s.frame_state(0).lods, s.frame_state(15).lods);
  EXPECT_EQ(s.frame_state(0).lods, s.frame_state(30).lods);
}

TEST(BuiltinCarousel, HasGlossyMaterialsAndMovingRing) {
  const Scene& s = cached("carousel");
  EXPECT_TRUE(std::any_of(s.materials.begin(), s.materials.end(), [](const Material& m) {
    return m.metallic == 1.0f && m.roughness == 0.3f;
  }));
  EXPECT_TRUE(std::any_of(s.materials.begin(), s.materials.end(), [](const Material& m) {
    return m.metallic == 0.0f && m.roughness == 0.2f;
  }));
  EXPECT_EQ(s.animation.tracks.size(), 8u);
  EXPECT_NE(s.frame_state(0).transforms, s.frame_state(1).transforms);
  EXPECT_GT(s.environment.radiance.r, 0.0f);
}

// carousel-bounce is carousel with the overhead light facing the back wall from 40 cm: every
// other mesh, material and track is carousel's.
TEST(BuiltinCarouselBounce, IsCarouselWithTheOverheadLightWashingTheBackWall) {
  const Scene& base = cached("carousel");
  const Scene& s = cached("carousel-bounce");
  ASSERT_EQ(s.meshes.size(), base.meshes.size());
  ASSERT_EQ(s.materials.size(), base.materials.size());
  EXPECT_EQ(s.animation.tracks.size(), base.animation.tracks.size());
  EXPECT_EQ(s.frame_state(7).transforms, base.frame_state(7).transforms);
  EXPECT_EQ(s.frame_state(7).camera.position, base.frame_state(7).camera.position);
  const Instance& light = instance_named(s, "light");
  for (size_t m = 0; m < s.meshes.size(); ++m) {
    const Primitive& p = s.meshes[m].primitives[0];
    if (m != light.lod_meshes[0]) {
      EXPECT_EQ(p.positions, base.meshes[m].primitives[0].positions) << s.meshes[m].name;
      continue;
    }
    for (const glm::vec3& v : p.positions) EXPECT_NEAR(v.z, -6.6f, 1e-5f);  // the wall is at z = -7
    const glm::vec3 a = p.positions[p.indices[0]], b = p.positions[p.indices[1]], c = p.positions[p.indices[2]];
    const glm::vec3 n = glm::cross(b - a, c - a);
    EXPECT_LT(n.z, 0.0f) << "faces the wall";
    EXPECT_EQ(s.materials[p.material].emission, glm::vec3(24.0f));
  }
}

TEST(BuiltinFoliage, BladesAreThousandsOfSubPixelTriangles) {
  const Scene& s = cached("foliage");
  const Instance& patch = instance_named(s, "grass_0");
  const Primitive& blades = s.meshes[patch.lod_meshes[0]].primitives[0];
  EXPECT_GE(blades.triangle_count(), 5'000u);
  // The first blade's base is narrower than 1 cm (a pixel at 256 px, 0.8 rad, 4 m is ~13 mm).
  EXPECT_LT(glm::length(blades.positions[1] - blades.positions[0]), 0.01f);
  EXPECT_TRUE(s.materials[blades.material].double_sided);
}

TEST(BuiltinStiff, SitsFarFromTheOriginWithExtremeEmitters) {
  const Scene& s = cached("stiff");
  EXPECT_GT(s.camera.position.x, 9.9e4f);
  for (const Instance& i : s.instances) EXPECT_GT(i.transform[3].x, 9.9e4f) << i.name;
  float lo = 1e30f, hi = 0.0f;
  for (const Material& m : s.materials) {
    if (m.emission.r > 0.0f) {
      lo = std::min(lo, m.emission.r);
      hi = std::max(hi, m.emission.r);
    }
  }
  EXPECT_GE(hi / lo, 1e7f);
  EXPECT_TRUE(std::any_of(s.materials.begin(), s.materials.end(), [](const Material& m) {
    return m.metallic == 1.0f && m.roughness <= 0.02f;
  }));
}

}  // namespace
}  // namespace strata::scene
