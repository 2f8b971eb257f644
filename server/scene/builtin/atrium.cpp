// atrium: a closed room lit only through openings, where most of what the camera sees is lit one or
// two bounces away from the light: the case ReSTIR's path reuse is for. The room (10 m x 14 m,
// 5 m high: x in [-5, 5], z in [-7, 7]) has a floor of stone tiles (a generated texture), plaster
// walls and ceiling, and no emitter inside. Light comes from a sun (a KHR_lights_punctual
// directional light, 8 lux, 49 degrees up from the -X side) and a sky (a generated 64 x 32 HDR
// map, blue with a glow about the sun and a dim ground below the horizon) through real holes in
// the geometry, each with a reveal (the wall's depth): three tall windows in the left wall, a
// clerestory band high in the back wall and a 3 m x 4 m skylight with a 0.6 m shaft. The sun
// draws bright patches on the floor under the left windows and, through the skylight, near the
// right wall; those patches light the rest of the room. Two columns stand at the back, a potted
// plant of alpha-masked (MASK, double-sided) leaf cards in the back right corner; a blue pillar slides to and
// fro through the skylight's sun patch and a crate turns in a window's patch. The camera dollies
// along the front wall, looking in. Deterministic; the tile texture is 64 x 64 texels.
#include <algorithm>
#include <cmath>
#include <utility>

#include <glm/gtc/matrix_transform.hpp>

#include "scene/builtin/builtins.h"
#include "scene/builtin/common.h"
#include "scene/builtin/random.h"
#include "scene/builtin/shapes.h"
#include "scene/builtin/textures.h"
#include "scene/environment_map.h"

namespace strata::scene::builtin {
namespace {

constexpr float kHalfWidth = 5.0f;   // x in [-5, 5]
constexpr float kHalfDepth = 7.0f;   // z in [-7, 7]
constexpr float kHeight = 5.0f;
constexpr float kWallDepth = 0.35f;  // the reveals of the windows
const glm::vec3 kSunTravel = glm::normalize(glm::vec3(0.55f, -0.75f, -0.35f));  // the way sunlight goes

// Stone tiles: 2 x 2 tiles of 32 texels with 2-texel grout, each tile its own shade and veining.
int32_t tile_texture(Scene& s) {
  Pcg32 rng(0xa7e1u);
  float shade[4];
  for (float& v : shade) v = rng.uniform(0.85f, 1.0f);
  return add_generated(s, "stone tiles", 64, 64, ColorSpace::kSrgb, [&](uint32_t x, uint32_t y) {
    if (x % 32 < 2 || y % 32 < 2) return rgba(0.35f, 0.33f, 0.3f);
    const float vein = tiled_noise(x + 2 * y, y, 8, 64, 7u);
    const float v = shade[(y / 32) * 2 + x / 32] * (0.86f + 0.14f * vein);
    return rgba(0.78f * v, 0.72f * v, 0.62f * v);
  });
}

// The sky: a horizon-to-zenith gradient, a glow about the sun (its disc is the directional
// light), a dim ground below the horizon. Row 0 looks up; the centre column looks down -Z and
// u grows towards +X (scene.h).
EnvironmentMap sky() {
  EnvironmentMap m;
  m.name = "atrium sky (generated)";
  m.width = 64;
  m.height = 32;
  const glm::vec3 to_sun = -kSunTravel;
  for (uint32_t y = 0; y < m.height; ++y) {
    const float elevation = 0.5f * kPi - (float(y) + 0.5f) / float(m.height) * kPi;
    for (uint32_t x = 0; x < m.width; ++x) {
      if (elevation < 0.0f) {
        m.radiance.emplace_back(0.2f, 0.18f, 0.14f);
        continue;
      }
      const float phi = ((float(x) + 0.5f) / float(m.width) - 0.5f) * 2.0f * kPi;
      const glm::vec3 dir(std::sin(phi) * std::cos(elevation), std::sin(elevation), -std::cos(phi) * std::cos(elevation));
      const float up = std::sqrt(std::sin(elevation));
      const glm::vec3 base = glm::vec3(0.75f, 0.82f, 0.95f) + up * (glm::vec3(0.25f, 0.42f, 0.85f) - glm::vec3(0.75f, 0.82f, 0.95f));
      const float glow = std::pow(std::max(glm::dot(dir, to_sun), 0.0f), 24.0f);
      m.radiance.push_back(base + glow * glm::vec3(2.0f, 1.8f, 1.4f));
    }
  }
  build_environment_tables(m);
  return m;
}

// The shell: floor, four walls and the ceiling, all facing in, with the openings cut out.
void add_room(SceneBuilder& b, uint32_t floor, uint32_t plaster) {
  Primitive tiles = quad({-kHalfWidth, 0, kHalfDepth}, {2 * kHalfWidth, 0, 0}, {0, 0, -2 * kHalfDepth}, floor);
  b.instance("floor", b.mesh("floor", {with_planar_uvs(tiles, {1, 0, 0}, {0, 0, 1})}));
  const glm::vec3 up(0, 1, 0);
  std::vector<Primitive> shell;
  // Left wall (x = -5, facing +X; s runs from z = 7 towards -Z): three windows 1.4 m wide.
  shell.push_back(wall_with_openings({-kHalfWidth, 0, kHalfDepth}, {0, 0, -1}, up, 2 * kHalfDepth, kHeight,
                                     {{2.3f, 3.7f, 0.8f, 3.6f}, {6.3f, 7.7f, 0.8f, 3.6f}, {10.3f, 11.7f, 0.8f, 3.6f}},
                                     kWallDepth, plaster));
  // Back wall (z = -7, facing +Z): a clerestory band.
  shell.push_back(wall_with_openings({-kHalfWidth, 0, -kHalfDepth}, {1, 0, 0}, up, 2 * kHalfWidth, kHeight,
                                     {{2.0f, 8.0f, 3.6f, 4.5f}}, kWallDepth, plaster));
  shell.push_back(wall_with_openings({kHalfWidth, 0, -kHalfDepth}, {0, 0, 1}, up, 2 * kHalfDepth, kHeight, {},
                                     kWallDepth, plaster));  // right wall, facing -X
  shell.push_back(wall_with_openings({kHalfWidth, 0, kHalfDepth}, {-1, 0, 0}, up, 2 * kHalfWidth, kHeight, {},
                                     kWallDepth, plaster));  // front wall, facing -Z
  // Ceiling (facing down; s along +X from x = -5, t along +Z from z = -7): the skylight and its shaft.
  shell.push_back(wall_with_openings({-kHalfWidth, kHeight, -kHalfDepth}, {1, 0, 0}, {0, 0, 1}, 2 * kHalfWidth,
                                     2 * kHalfDepth, {{3.5f, 6.5f, 5.0f, 9.0f}}, 0.6f, plaster));
  b.instance("shell", b.mesh("shell", shell));
  // Outside: open ground under the sky, seen (and bounced off) through the windows.
  const uint32_t ground = b.matte("ground", {0.3f, 0.28f, 0.2f});
  b.instance("ground", b.mesh("ground", {quad({-30, -0.02f, 30}, {60, 0, 0}, {0, 0, -60}, ground)}));
}

void add_furniture(SceneBuilder& b, uint32_t stone, uint32_t leaf) {
  Primitive columns;
  columns.material = stone;
  for (const float x : {-2.2f, 2.2f})
    append(columns, transformed(cylinder(0.3f, kHeight, 12, stone), glm::translate(glm::mat4(1.0f), {x, 0.0f, -5.2f})));
  b.instance("columns", b.mesh("columns", {columns}));

  const uint32_t clay = b.matte("terracotta", {0.55f, 0.27f, 0.16f});
  const Primitive pot = cylinder(0.3f, 0.5f, 10, clay);
  const Primitive crown = leaf_cards(32, 8, 0.5f, 0.3f, 0.55f, 0.2f, leaf, 0xa11u);
  b.instance("plant", b.mesh("plant", {pot, crown}), glm::translate(glm::mat4(1.0f), {4.1f, 0.0f, -6.1f}));

  // The pillar slides along z through the skylight's sun patch and back, once over the animation.
  const uint32_t paint = b.material("blue paint", {0.15f, 0.25f, 0.55f}, 0.0f, 0.4f);
  const uint32_t pillar = b.instance("pillar", b.mesh("pillar", {box({0.2f, 1.2f, 0.2f}, paint)}));
  b.track(pillar, [](uint32_t f) {
    TransformKey k;
    k.translation = {3.0f, 1.2f, -2.3f - 1.8f * std::sin(2.0f * kPi * float(f) / float(kFrameCount))};
    return k;
  });
  // The crate turns a quarter turn about +Y in the middle window's sun patch.
  const uint32_t wood = b.material("wood", {0.45f, 0.3f, 0.18f}, 0.0f, 0.7f);
  const uint32_t crate = b.instance("crate", b.mesh("crate", {box({0.45f, 0.45f, 0.45f}, wood)}));
  b.track(crate, [](uint32_t f) {
    TransformKey k;
    k.translation = {-3.0f, 0.45f, -1.4f};
    k.rotation = glm::angleAxis(0.5f * kPi * float(f) / float(kFrameCount - 1), glm::vec3(0, 1, 0));
    return k;
  });
}

}  // namespace

Scene make_atrium() {
  SceneBuilder b("atrium");
  Scene& s = b.scene();
  const uint32_t floor = b.material("stone tiles", glm::vec3(1.0f), 0.0f, 0.6f);
  s.materials[floor].base_color_texture.texture = tile_texture(s);
  s.materials[floor].base_color_texture.transform.scale = glm::vec2(0.5f);  // 1 m tiles
  const uint32_t plaster = b.matte("plaster", {0.78f, 0.76f, 0.72f});
  const uint32_t stone = b.matte("column stone", {0.7f, 0.68f, 0.64f});
  const uint32_t leaf = b.material("leaf", glm::vec3(1.0f), 0.0f, 0.6f);
  s.materials[leaf].double_sided = true;
  s.materials[leaf].alpha_mode = AlphaMode::kMask;
  s.materials[leaf].base_color_texture.texture = leaf_texture(s);

  add_room(b, floor, plaster);
  add_furniture(b, stone, leaf);
  b.light(light_at("sun", LightType::kDirectional, {1.0f, 0.93f, 0.82f}, 8.0f, glm::vec3(0.0f), kSunTravel));
  s.environment.map = sky();

  auto dolly = [](uint32_t f) {
    const float t = float(f) / float(kFrameCount - 1);
    return std::pair{glm::vec3(3.2f - 4.0f * t, 1.7f, 6.2f), glm::vec3(-1.0f, 1.4f, -3.0f)};
  };
  b.camera(dolly(0).first, dolly(0).second, 1.05f);
  b.camera_path(dolly);
  return b.finish();
}

}  // namespace strata::scene::builtin
