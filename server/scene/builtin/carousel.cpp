// carousel: eight objects (boxes, UV spheres, cylinders) on a ring turning about +Y in front of a
// layered backdrop: a row of pillars, a row of horizontal slats, a row of panels with gaps, a row
// of thin posts and a back wall. A camera ray through the gaps crosses 3-5 surfaces, and the
// turning ring uncovers new backdrop every frame (disocclusion). Materials mix matte, metal
// (metallic 1, roughness 0.3) and glossy dielectric (roughness 0.2). Light: two emissive quads
// (overhead, radiance 6; side, radiance 3) and a dim environment 0.05. Animation: the ring turns 90
// degrees over 120 frames (a key per frame per object); the camera pans from left to right while
// aiming at the ring's centre.
//
// carousel-bounce: the same scene with the overhead light turned into a wall washer (radiance 24,
// 40 cm in front of the back wall's top, facing it), so most light reaches the ring after one
// bounce off the bright patch it makes, which next-event estimation cannot aim at: the light that
// ReSTIR PT is for (docs/BENCHMARKS.md, "Where the lighting is hard").
#include <cmath>
#include <utility>

#include <glm/gtc/matrix_transform.hpp>

#include "scene/builtin/builtins.h"
#include "scene/builtin/common.h"
#include "scene/builtin/shapes.h"

namespace strata::scene::builtin {
namespace {

constexpr uint32_t kRingObjects = 8;
constexpr float kRingRadius = 2.2f;

// The backdrop: rows at increasing depth behind the ring, each one merged mesh.
void add_backdrop(SceneBuilder& b, uint32_t pillar_material, uint32_t slat_material,
                  uint32_t panel_material, uint32_t wall_material) {
  Primitive pillars;
  pillars.material = pillar_material;
  for (int i = -7; i <= 7; ++i) {
    const glm::mat4 at =
        glm::translate(glm::mat4(1.0f), {0.8f * static_cast<float>(i), 0.0f, -3.5f});
    append(pillars, transformed(cylinder(0.12f, 1.0f, 24, pillar_material),
                                glm::scale(at, {1.0f, 4.0f, 1.0f})));
  }
  b.instance("pillars", b.mesh("pillars", {std::move(pillars)}));

  Primitive slats;
  slats.material = slat_material;
  for (int k = 0; k < 6; ++k) {
    const glm::vec3 center(0.0f, 0.4f + 0.6f * static_cast<float>(k), -4.5f);
    append(slats, transformed(box({6.0f, 0.08f, 0.05f}, slat_material),
                              glm::translate(glm::mat4(1.0f), center)));
  }
  b.instance("slats", b.mesh("slats", {std::move(slats)}));

  Primitive panels;
  panels.material = panel_material;
  for (int i = -4; i <= 4; ++i) {
    const float x = 1.3f * static_cast<float>(i);
    const float y = (i % 2 == 0) ? 1.2f : 2.4f;  // staggered heights leave gaps above and below
    append(panels, facing_quad({x, y, -5.5f}, {0, 0, 1}, 0.9f, 1.6f, panel_material));
  }
  b.instance("panels", b.mesh("panels", {std::move(panels)}));

  Primitive posts;
  posts.material = pillar_material;
  for (int i = -10; i <= 10; ++i) {
    const glm::vec3 center(0.55f * static_cast<float>(i) + 0.2f, 2.0f, -6.2f);
    append(posts, transformed(box({0.05f, 2.0f, 0.05f}, pillar_material),
                              glm::translate(glm::mat4(1.0f), center)));
  }
  b.instance("posts", b.mesh("posts", {std::move(posts)}));

  b.instance("wall", b.mesh("wall", {quad({-10, 0, -7}, {20, 0, 0}, {0, 6, 0}, wall_material)}));
}

// The overhead light: a 2 m x 1 m emissive quad.
struct OverheadLight {
  glm::vec3 centre;
  glm::vec3 facing;
  float radiance;
};
constexpr OverheadLight k_ceiling_light{{0.0f, 5.0f, 0.5f}, {0, -1, 0}, 6.0f};
constexpr OverheadLight k_wall_washer{{0.0f, 5.4f, -6.6f}, {0, 0, -1}, 24.0f};  // 40 cm from the wall

Scene carousel_lit(const char* scene_name, const OverheadLight& overhead) {
  SceneBuilder b(scene_name);
  const uint32_t floor = b.material("floor", {0.5f, 0.5f, 0.5f}, 0.0f, 0.8f);
  const uint32_t gold = b.material("gold_metal", {1.0f, 0.78f, 0.34f}, 1.0f, 0.3f);
  const uint32_t red_glossy = b.material("red_glossy", {0.7f, 0.08f, 0.06f}, 0.0f, 0.2f);
  const uint32_t blue = b.material("blue_matte", {0.1f, 0.2f, 0.6f});
  const uint32_t pillar = b.material("pillar", {0.75f, 0.72f, 0.68f});
  const uint32_t slat = b.material("slat", {0.35f, 0.22f, 0.12f}, 0.0f, 0.6f);
  const uint32_t panel = b.material("panel", {0.2f, 0.45f, 0.3f});
  const uint32_t wall = b.material("wall", {0.6f, 0.6f, 0.62f});
  const uint32_t light = b.emitter("light", glm::vec3(overhead.radiance));
  const uint32_t side_light = b.emitter("side_light", {3.0f, 2.6f, 2.2f});

  b.instance("floor", b.mesh("floor", {quad({-10, 0, 10}, {20, 0, 0}, {0, 0, -20}, floor)}));
  add_backdrop(b, pillar, slat, panel, wall);

  // Ring objects: shapes rest on the turntable plane y = 0.
  const uint32_t shape_materials[3] = {gold, red_glossy, blue};
  std::vector<uint32_t> ring;
  for (uint32_t k = 0; k < kRingObjects; ++k) {
    const uint32_t material = shape_materials[k % 3];
    Primitive shape;
    const char* kind = "";
    switch (k % 3) {
      case 0:
        shape = transformed(box({0.35f, 0.35f, 0.35f}, material),
                            glm::translate(glm::mat4(1.0f), {0, 0.35f, 0}));
        kind = "box";
        break;
      case 1:
        shape = transformed(uv_sphere(0.4f, 16, 16, material),
                            glm::translate(glm::mat4(1.0f), {0, 0.4f, 0}));
        kind = "sphere";
        break;
      default:
        shape = cylinder(0.3f, 0.9f, 32, material);
        kind = "cylinder";
        break;
    }
    const std::string name = std::string(kind) + "_" + std::to_string(k);
    ring.push_back(b.instance(name, b.mesh(name, {std::move(shape)})));
  }
  for (uint32_t k = 0; k < kRingObjects; ++k) {
    const float phase = 2.0f * kPi * static_cast<float>(k) / static_cast<float>(kRingObjects);
    b.track(ring[k], [&](uint32_t f) {
      const float angle =
          phase + 0.5f * kPi * static_cast<float>(f) / static_cast<float>(kFrameCount - 1);
      TransformKey key;
      key.translation = {kRingRadius * std::cos(angle), 0.0f, -kRingRadius * std::sin(angle)};
      key.rotation = glm::angleAxis(angle, glm::vec3(0.0f, 1.0f, 0.0f));
      return key;
    });
  }

  b.instance("light", b.mesh("light", {facing_quad(overhead.centre, overhead.facing, 2.0f, 1.0f, light)}));
  b.instance("side_light", b.mesh("side_light", {facing_quad({-6.0f, 2.5f, 2.0f}, {1, -0.3f, -0.2f},
                                                             1.2f, 1.2f, side_light)}));
  b.scene().environment.radiance = glm::vec3(0.05f);

  b.camera({-1.5f, 1.6f, 6.0f}, {0.0f, 1.0f, -1.0f}, 0.8f);
  b.camera_path([](uint32_t f) {
    const float s = static_cast<float>(f) / static_cast<float>(kFrameCount - 1);
    return std::pair{glm::vec3(-1.5f + 3.0f * s, 1.6f, 6.0f), glm::vec3(0.0f, 1.0f, -1.0f)};
  });
  return b.finish();
}

}  // namespace

Scene make_carousel() { return carousel_lit("carousel", k_ceiling_light); }

Scene make_carousel_bounce() { return carousel_lit("carousel-bounce", k_wall_washer); }

}  // namespace strata::scene::builtin
