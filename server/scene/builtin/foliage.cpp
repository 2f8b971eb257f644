// foliage: sub-pixel geometry. Four patches (one shared mesh, four instances) of 1,500 grass
// blades each, 6-10 mm wide at the base (a pixel at 256 x 256 covers about 13 mm at 4 m) and
// 15-40 cm tall, each blade three thin triangles bending away from the vertical; plus 1,200
// small leaves (3 cm quads) lying on the ground. Blades and leaves are double-sided.
// Light: a sun quad (4 m x 4 m at 400 m, radiance ~2.5e4) and a sky environment (0.3, 0.4, 0.55).
// Animation: the camera slides 4 m sideways at 1.2 m height, looking slightly down.
#include <cmath>
#include <utility>

#include <glm/gtc/matrix_transform.hpp>

#include "scene/builtin/builtins.h"
#include "scene/builtin/common.h"
#include "scene/builtin/random.h"
#include "scene/builtin/shapes.h"
#include "scene/normals.h"

namespace strata::scene::builtin {
namespace {

constexpr uint32_t kBladesPerPatch = 1500;
constexpr uint32_t kLeaves = 1200;
constexpr float kPatchSize = 4.0f;

// One blade: a tapered strip of two quads and a tip, curving in its facing plane.
void add_blade(Primitive& p, Pcg32& rng) {
  // One draw per statement: the order of evaluation of function arguments is unspecified.
  const float x = rng.uniform(-0.5f, 0.5f) * kPatchSize;
  const float z = rng.uniform(-0.5f, 0.5f) * kPatchSize;
  const glm::vec3 root(x, 0.0f, z);
  const float height = rng.uniform(0.15f, 0.4f);
  const float width = rng.uniform(0.006f, 0.01f);
  const float heading = rng.uniform(0.0f, 2.0f * kPi);
  const float lean = rng.uniform(0.05f, 0.35f);  // how far the tip bends, relative to height
  const glm::vec3 side(std::cos(heading), 0.0f, std::sin(heading));
  const glm::vec3 bend(-side.z, 0.0f, side.x);
  const uint32_t base = static_cast<uint32_t>(p.positions.size());
  for (uint32_t level = 0; level < 3; ++level) {
    const float t = static_cast<float>(level) / 3.0f;
    const glm::vec3 centre =
        root + glm::vec3(0.0f, height * t, 0.0f) + bend * (lean * height * t * t);
    const float half = 0.5f * width * (1.0f - t);
    p.positions.push_back(centre - side * half);
    p.positions.push_back(centre + side * half);
    p.uvs.emplace_back(0.0f, t);
    p.uvs.emplace_back(1.0f, t);
  }
  p.positions.push_back(root + glm::vec3(0.0f, height, 0.0f) + bend * (lean * height));
  p.uvs.emplace_back(0.5f, 1.0f);
  for (uint32_t level = 0; level < 2; ++level) {
    const uint32_t a = base + 2 * level;
    p.indices.insert(p.indices.end(), {a, a + 1, a + 3, a, a + 3, a + 2});
  }
  p.indices.insert(p.indices.end(), {base + 4, base + 5, base + 6});
}

Primitive grass_patch(uint32_t material) {
  Pcg32 rng(0xb1ade5u);
  Primitive p;
  p.material = material;
  for (uint32_t i = 0; i < kBladesPerPatch; ++i) add_blade(p, rng);
  p.normals = area_weighted_normals(p.positions, p.indices);
  return p;
}

Primitive leaves(uint32_t material) {
  Pcg32 rng(0x1eafu);
  Primitive p;
  p.material = material;
  for (uint32_t i = 0; i < kLeaves; ++i) {
    const float x = rng.uniform(-4.0f, 4.0f);
    const float y = 0.004f + 0.01f * rng.uniform();
    const float z = rng.uniform(-4.0f, 2.0f);
    const float heading = rng.uniform(0.0f, 2.0f * kPi);
    const float tilt = 0.15f * rng.uniform(-1.0f, 1.0f);
    const glm::vec3 centre(x, y, z);
    const glm::vec3 u = 0.03f * glm::vec3(std::cos(heading), 0.0f, -std::sin(heading));
    const glm::vec3 v = 0.02f * glm::vec3(-std::sin(heading), tilt, -std::cos(heading));
    // cross(u, v) points up: u = (c, 0, -s), v = (-s, ., -c) gives y = s*s + c*c.
    append(p, quad(centre - 0.5f * u - 0.5f * v, u, v, material));
  }
  return p;
}

}  // namespace

Scene make_foliage() {
  SceneBuilder b("foliage");
  const uint32_t soil = b.material("soil", {0.3f, 0.22f, 0.15f});
  const uint32_t grass = b.material("grass", {0.2f, 0.5f, 0.1f}, 0.0f, 0.6f);
  b.scene().materials[grass].double_sided = true;
  const uint32_t leaf = b.material("leaf", {0.5f, 0.35f, 0.1f}, 0.0f, 0.7f);
  b.scene().materials[leaf].double_sided = true;
  const uint32_t sun = b.emitter("sun", {25000.0f, 24000.0f, 21000.0f});

  b.instance("ground", b.mesh("ground", {quad({-10, 0, 10}, {20, 0, 0}, {0, 0, -20}, soil)}));
  const uint32_t patch = b.mesh("grass_patch", {grass_patch(grass)});
  const glm::vec3 offsets[4] = {{-2, 0, -2}, {2, 0, -2}, {-2, 0, 2}, {2, 0, 2}};
  for (int k = 0; k < 4; ++k) {
    // A quarter turn per patch keeps the shared mesh from tiling visibly.
    const glm::mat4 m =
        glm::rotate(glm::translate(glm::mat4(1.0f), offsets[k] + glm::vec3(0, 0, -1)),
                    0.5f * kPi * static_cast<float>(k), glm::vec3(0, 1, 0));
    b.instance("grass_" + std::to_string(k), patch, m);
  }
  b.instance("leaves", b.mesh("leaves", {leaves(leaf)}));

  const glm::vec3 sun_direction = glm::normalize(glm::vec3(0.4f, 0.7f, 0.3f));
  b.instance("sun",
             b.mesh("sun", {facing_quad(400.0f * sun_direction, -sun_direction, 4.0f, 4.0f, sun)}));
  b.scene().environment.radiance = {0.3f, 0.4f, 0.55f};

  auto slide = [](uint32_t f) {
    const float x = -2.0f + 4.0f * static_cast<float>(f) / static_cast<float>(kFrameCount - 1);
    return std::pair{glm::vec3(x, 1.2f, 4.0f), glm::vec3(x, 0.1f, -1.0f)};
  };
  b.camera(slide(0).first, slide(0).second, 0.8f);
  b.camera_path(slide);
  return b.finish();
}

}  // namespace strata::scene::builtin
