// lod-bounce: LoD switches where history pays. Five large objects (three UV spheres and two
// lathed vases, 5,900-9,200 triangles at level 0) stand in a row across a closed room and fill most
// of the image; each has three LoD levels from make_lod_chain, every level half the triangles of
// the one before (not a quarter, so a switch changes the surface a little, as a game's LoD does).
// Light: as carousel-bounce, a wall washer (a 6 m x 1 m quad of radiance 12, 80 cm in front of the
// back wall's top, facing it) in a closed room: most of what the objects receive comes after one
// bounce off the lit patch of wall, which next-event estimation cannot aim at, and ReSTIR PT's
// history is worth many frames there.
// Animation: the objects turn about their own axes (a quarter turn over 120 frames, alternately
// clockwise and counter-clockwise) and the camera dollies 1 m towards them; every object switches
// from level 2 to level 1 at frame 8 and to level 0 at frame 40 (the spheres) or 48 (the vases).
#include <cmath>
#include <string>
#include <utility>

#include <glm/gtc/matrix_transform.hpp>

#include "scene/builtin/builtins.h"
#include "scene/builtin/common.h"
#include "scene/builtin/shapes.h"
#include "scene/lod.h"

namespace strata::scene::builtin {
namespace {

constexpr uint32_t kLevels = 3;
constexpr float kLevelRatio = 0.5f;

Primitive vase(uint32_t material) {
  std::vector<ProfilePoint> profile;
  for (uint32_t i = 0; i <= 40; ++i) {
    const float t = static_cast<float>(i) / 40.0f;
    const float radius = 0.25f + 0.3f * std::sin(kPi * (0.15f + 0.8f * t)) + 0.06f * std::sin(6.0f * kPi * t);
    profile.push_back({radius, 1.6f * t});
  }
  profile.push_back({0.0f, 1.6f});
  return lathe(profile, 112, material);
}

}  // namespace

Scene make_lod_bounce() {
  SceneBuilder b("lod-bounce");
  const uint32_t floor = b.material("floor", {0.5f, 0.5f, 0.5f}, 0.0f, 0.8f);
  const uint32_t wall = b.matte("wall", {0.7f, 0.7f, 0.72f});
  const uint32_t side = b.matte("side_wall", {0.55f, 0.35f, 0.3f});
  const uint32_t clay = b.matte("clay", {0.75f, 0.55f, 0.4f});
  const uint32_t glaze = b.material("glaze", {0.15f, 0.3f, 0.6f}, 0.0f, 0.35f);
  const uint32_t bronze = b.material("bronze", {0.8f, 0.5f, 0.3f}, 1.0f, 0.4f);
  const uint32_t washer = b.emitter("wall_washer", glm::vec3(12.0f));

  // The room: 10 m wide, 8 m deep, 5 m high, closed (the front wall is behind the camera).
  b.instance("floor", b.mesh("floor", {quad({-5, 0, 4}, {10, 0, 0}, {0, 0, -8}, floor)}));
  b.instance("back_wall", b.mesh("back_wall", {quad({-5, 0, -4}, {10, 0, 0}, {0, 5, 0}, wall)}));
  b.instance("ceiling", b.mesh("ceiling", {quad({-5, 5, -4}, {10, 0, 0}, {0, 0, 8}, wall)}));
  b.instance("left_wall", b.mesh("left_wall", {quad({-5, 0, 4}, {0, 0, -8}, {0, 5, 0}, side)}));
  b.instance("right_wall", b.mesh("right_wall", {quad({5, 0, -4}, {0, 0, 8}, {0, 5, 0}, side)}));
  b.instance("front_wall", b.mesh("front_wall", {quad({5, 0, 4}, {-10, 0, 0}, {0, 5, 0}, wall)}));
  b.instance("wall_washer", b.mesh("wall_washer", {facing_quad({0.0f, 4.3f, -3.2f}, {0, 0, -1}, 6.0f, 1.0f, washer)}));

  // The row of objects, each with its LoD chain.
  const float xs[5] = {-3.2f, -1.6f, 0.0f, 1.6f, 3.2f};
  std::vector<uint32_t> objects;
  std::vector<bool> is_vase;
  for (uint32_t k = 0; k < 5; ++k) {
    const bool v = k % 2 == 1;
    const uint32_t material = v ? glaze : (k == 2 ? bronze : clay);
    const Primitive level0 =
        v ? vase(material) : transformed(uv_sphere(0.7f, 64, 48, material), glm::translate(glm::mat4(1.0f), {0, 0.7f, 0}));
    const std::string name = std::string(v ? "vase_" : "sphere_") + std::to_string(k);
    std::vector<uint32_t> levels;
    const auto chain = make_lod_chain(level0, kLevels, kLevelRatio, /*lock_border=*/true);
    for (size_t l = 0; l < chain.size(); ++l) levels.push_back(b.mesh(name + "_lod" + std::to_string(l), {chain[l]}));
    const uint32_t start = std::min<uint32_t>(2, static_cast<uint32_t>(levels.size() - 1));
    objects.push_back(b.instance(name, levels, glm::translate(glm::mat4(1.0f), {xs[k], 0.0f, -1.0f}), start));
    is_vase.push_back(v);
  }
  for (uint32_t k = 0; k < objects.size(); ++k) {
    const float turn = (k % 2 == 0 ? 1.0f : -1.0f) * 0.5f * kPi;
    b.track(objects[k], [&](uint32_t f) {
      TransformKey key;
      key.translation = {xs[k], 0.0f, -1.0f};
      key.rotation = glm::angleAxis(turn * static_cast<float>(f) / static_cast<float>(kFrameCount - 1), glm::vec3(0, 1, 0));
      return key;
    });
    b.lod_key(0, objects[k], 2);
    b.lod_key(8, objects[k], 1);
    b.lod_key(is_vase[k] ? 48 : 40, objects[k], 0);
  }
  b.scene().environment.radiance = glm::vec3(0.0f);

  const glm::vec3 target(0.0f, 0.8f, -1.0f);
  b.camera({0.0f, 1.5f, 3.8f}, target, 0.9f);
  b.camera_path([&](uint32_t f) {
    const float s = static_cast<float>(f) / static_cast<float>(kFrameCount - 1);
    return std::pair{glm::mix(glm::vec3(0.0f, 1.5f, 3.8f), glm::vec3(0.3f, 1.4f, 2.8f), s), target};
  });
  return b.finish();
}

}  // namespace strata::scene::builtin
