// night-street: a street at night, the many-light case of a game level, where light selection in
// proportion to power wastes most samples and ReSTIR's resampling should beat plain path tracing.
// A road (asphalt texture, a dashed centre line) between two raised sidewalks (paving slabs) runs
// 66 m past six buildings a side (stone facades, three tints of one texture, 12-18 m tall) to a
// cross street closed by a far facade with a billboard. Every facade has a grid of windows, small
// quads 2 cm in front of it: most lit (six emissive materials, warm to cool, radiance 0.2-1.5), some
// dark glass; each building has a dark shop window and most a three-bar neon sign (emissive).
// Five small trees of alpha-masked (MASK, double-sided) leaf cards stand on the sidewalks. The
// 64 punctual lights (street lamps, shop lights, swaying lanterns, two driving cars with their
// headlights and tail lights, far floodlights and high masts) are night_street_lights.cpp's. The
// sky is a dim 32 x 16 night map (most light comes from the lamps and windows). The camera walks
// 8 m down the left sidewalk over the 120 frames, with a slight step bob. Textures are generated
// here (deterministic), 64 x 64 texels or smaller.
#include <algorithm>
#include <cmath>
#include <map>
#include <string>
#include <utility>

#include <glm/gtc/matrix_transform.hpp>

#include "scene/builtin/builtins.h"
#include "scene/builtin/night_street.h"
#include "scene/builtin/random.h"
#include "scene/builtin/shapes.h"
#include "scene/builtin/textures.h"
#include "scene/environment_map.h"

namespace strata::scene::builtin {
namespace {

using namespace night_street;

// A texture on `m` whose UVs are metres (with_planar_uvs): one tile every `metres`.
void tile(Material& m, int32_t texture, float metres) {
  m.base_color_texture.texture = texture;
  m.base_color_texture.transform.scale = glm::vec2(1.0f / metres);
}

// Asphalt: dark grey grain with lighter chips.
int32_t asphalt(Scene& s) {
  return add_generated(s, "asphalt", 64, 64, ColorSpace::kSrgb, [](uint32_t x, uint32_t y) {
    const float grain = 0.7f * tiled_noise(x, y, 8, 64, 1u) + 0.3f * tiled_noise(x, y, 2, 64, 2u);
    const float chip = (hash2(int32_t(x), int32_t(y), 3u) & 31u) == 0 ? 0.1f : 0.0f;
    const float v = 0.16f + 0.08f * grain + chip;
    return rgba(v, v, 1.05f * v);
  });
}

// Paving: 2 x 2 concrete slabs of 32 texels with 1-texel joints, each slab its own shade, stained.
int32_t paving(Scene& s) {
  Pcg32 rng(0x5a1bu);
  float shade[4];
  for (float& v : shade) v = rng.uniform(0.8f, 1.0f);
  return add_generated(s, "paving slabs", 64, 64, ColorSpace::kSrgb, [&](uint32_t x, uint32_t y) {
    if (x % 32 == 0 || y % 32 == 0) return rgba(0.22f, 0.22f, 0.21f);
    const float v = shade[(y / 32) * 2 + x / 32] * (0.85f + 0.15f * tiled_noise(x, y, 8, 64, 4u));
    return rgba(0.55f * v, 0.54f * v, 0.5f * v);
  });
}

// Ashlar: 4 courses of two 32 x 16 blocks, every other course offset by half a block, 1-texel
// joints, weathered (white: materials tint it).
int32_t ashlar(Scene& s) {
  return add_generated(s, "ashlar", 64, 64, ColorSpace::kSrgb, [](uint32_t x, uint32_t y) {
    const uint32_t course = y / 16, shifted = (x + (course % 2) * 16) % 64;
    if (y % 16 == 0 || shifted % 32 == 0) return rgba(0.45f, 0.43f, 0.4f);
    const float block = float(hash2(int32_t(course), int32_t(shifted / 32), 5u) >> 24) / 255.0f;
    const float v = (0.82f + 0.12f * block) * (0.88f + 0.12f * tiled_noise(x, y, 4, 64, 6u));
    return rgba(v, v, v);
  });
}

// A night sky: a faint glow of the city at the horizon fading to a near-black zenith.
EnvironmentMap night_sky() {
  EnvironmentMap m;
  m.name = "night-street sky (generated)";
  m.width = 32;
  m.height = 16;
  for (uint32_t y = 0; y < m.height; ++y) {
    const float elevation = 0.5f * kPi - (float(y) + 0.5f) / float(m.height) * kPi;
    const float h = elevation < 0.0f ? 0.0f : std::exp(-5.0f * elevation);
    const glm::vec3 sky = glm::vec3(0.002f, 0.003f, 0.008f) + h * glm::vec3(0.014f, 0.01f, 0.008f);
    for (uint32_t x = 0; x < m.width; ++x) m.radiance.push_back(elevation < 0.0f ? glm::vec3(0.001f) : sky);
  }
  build_environment_tables(m);
  return m;
}

// Windows and signs, one primitive per material, collected while the facades are laid out.
struct Panes {
  std::map<uint32_t, Primitive> by_material;
  void add(const glm::vec3& center, const glm::vec3& normal, float w, float h, uint32_t material) {
    Primitive& group = by_material[material];
    group.material = material;
    append(group, facing_quad(center, normal, w, h, material));
  }
};

struct Palette {
  uint32_t lit[6];   // window emitters
  uint32_t neon[4];  // sign emitters
  uint32_t glass;
  uint32_t facade[3];
  uint32_t billboard;
};

// A facade's windows (0.9 m x 1.6 m, 2 cm out along `normal`): `columns` columns 1.3 m apart from
// `first` along `along`, floors 3 m apart from 5 m up while a window fits 0.8 m under the top `height`;
// 85% lit, the rest dark glass. `skip(center)` leaves a window out.
template <typename Skip>
void windows(Panes& panes, const Palette& p, Pcg32& rng, glm::vec3 first, glm::vec3 along, glm::vec3 normal,
             uint32_t columns, float height, Skip skip) {
  for (float y = 5.0f; y + 1.6f <= height; y += 3.0f) {
    for (uint32_t c = 0; c < columns; ++c) {
      const glm::vec3 center = first + 1.3f * float(c) * along + glm::vec3(0.0f, y, 0.0f) + 0.02f * normal;
      if (skip(center)) continue;
      const bool lit = rng.uniform() < 0.85f;
      panes.add(center, normal, 0.9f, 1.6f, lit ? p.lit[rng.next() % 6] : p.glass);
    }
  }
}

void add_street(SceneBuilder& b, uint32_t road, uint32_t walk, uint32_t paint) {
  const glm::vec3 x(1, 0, 0), z(0, 0, 1);
  const float length = kNearZ - kCrossZ, crossing = kCrossZ - kFarFacadeZ;
  Primitive ground = quad({-kRoadHalfWidth, 0, kNearZ}, {2 * kRoadHalfWidth, 0, 0}, {0, 0, -length}, road);
  append(ground, quad({-30, 0, kCrossZ}, {60, 0, 0}, {0, 0, -crossing}, road));
  b.instance("road", b.mesh("road", {with_planar_uvs(ground, x, z)}));
  Primitive walks;
  walks.material = walk;
  for (const float side : {-1.0f, 1.0f}) {
    const float inner = side * kRoadHalfWidth, outer = side * kFacadeX, lo = std::min(inner, outer);
    append(walks, quad({lo, kCurb, kNearZ}, {kFacadeX - kRoadHalfWidth, 0, 0}, {0, 0, -length}, walk));
    // The curb faces the road; the sidewalk's end faces the cross street.
    append(walks, side < 0 ? quad({inner, 0, kNearZ}, {0, 0, -length}, {0, kCurb, 0}, walk)
                           : quad({inner, 0, kCrossZ}, {0, 0, length}, {0, kCurb, 0}, walk));
    append(walks, quad({lo + kFacadeX - kRoadHalfWidth, 0, kCrossZ}, {kRoadHalfWidth - kFacadeX, 0, 0}, {0, kCurb, 0}, walk));
  }
  b.instance("sidewalks", b.mesh("sidewalks", {with_planar_uvs(walks, x, z)}));
  Primitive dashes;
  dashes.material = paint;
  for (float z0 = kNearZ - 1.0f; z0 - 3.0f > kCrossZ; z0 -= 6.0f)
    append(dashes, quad({-0.075f, 0.005f, z0}, {0.15f, 0, 0}, {0, 0, -3}, paint));
  b.instance("centre line", b.mesh("centre line", {dashes}));
}

// Six buildings a side and the far facade, with their windows, shop windows and signs.
void add_buildings(SceneBuilder& b, const Palette& p) {
  Pcg32 rng(0xb0d1e5u);
  Panes panes;
  std::vector<Primitive> facades;
  for (uint32_t side_index = 0; side_index < 2; ++side_index) {
    const float side = side_index == 0 ? -1.0f : 1.0f;
    const glm::vec3 normal(-side, 0.0f, 0.0f), along(0.0f, 0.0f, -1.0f);
    for (uint32_t k = 0; k < kBlocks; ++k) {
      const float z0 = kNearZ - kBlockLength * float(k), height = rng.uniform(12.0f, 18.0f);
      const uint32_t material = p.facade[(k + side_index) % 3];
      const glm::vec3 corner(side * kFacadeX, 0.0f, side < 0 ? z0 : z0 - kBlockLength);
      facades.push_back(quad(corner, {0, 0, side < 0 ? -kBlockLength : kBlockLength}, {0, height, 0}, material));
      windows(panes, p, rng, glm::vec3(side * kFacadeX, 0.0f, z0 - 0.95f), along, normal, 8, height,
              [](const glm::vec3&) { return false; });
      const glm::vec3 shop(side * (kFacadeX - 0.02f), 1.55f, z0 - 0.5f * kBlockLength);
      panes.add(shop, normal, 5.0f, 2.1f, p.glass);
      if (rng.uniform() < 0.7f) {
        const uint32_t neon = p.neon[rng.next() % 4];
        for (const float dz : {-1.4f, 0.0f, 1.4f})
          panes.add(shop + glm::vec3(-side * 0.02f, 1.7f, dz), normal, 1.2f, 0.35f, neon);
      }
    }
  }
  // The far facade across the cross street, its billboard (lit by the floodlights) and windows.
  facades.push_back(quad({-30, 0, kFarFacadeZ}, {60, 0, 0}, {0, 20, 0}, p.facade[1]));
  panes.add({0.0f, 10.5f, kFarFacadeZ + 0.03f}, {0, 0, 1}, 10.0f, 5.0f, p.billboard);
  windows(panes, p, rng, {-14.0f, 0.0f, kFarFacadeZ}, {1, 0, 0}, {0, 0, 1}, 22, 20.0f, [](const glm::vec3& c) {
    return std::abs(c.x) < 6.0f && c.y > 7.0f && c.y < 14.0f;
  });
  for (Primitive& f : facades) f = with_planar_uvs(f, f.normals[0].x != 0.0f ? glm::vec3(0, 0, 1) : glm::vec3(1, 0, 0), {0, 1, 0});
  b.instance("facades", b.mesh("facades", facades));
  std::vector<Primitive> lit;
  for (auto& [material, primitive] : panes.by_material) lit.push_back(std::move(primitive));
  b.instance("windows and signs", b.mesh("windows and signs", lit));
}

void add_trees(SceneBuilder& b, uint32_t bark, uint32_t leaf) {
  const Primitive trunk = cylinder(0.08f, 2.2f, 6, bark);
  const Primitive crown = leaf_cards(36, 9, 1.7f, 0.35f, 0.6f, 0.3f, leaf, 0x7ee5u);
  const uint32_t tree = b.mesh("tree", {trunk, crown});
  const glm::vec2 spots[5] = {{-5.6f, -8.0f}, {-5.6f, -24.0f}, {-5.6f, -40.0f}, {5.6f, -16.0f}, {5.6f, -32.0f}};
  for (uint32_t k = 0; k < 5; ++k) {
    const glm::mat4 at = glm::rotate(glm::translate(glm::mat4(1.0f), {spots[k].x, kCurb, spots[k].y}), float(k) * 1.3f,
                                     glm::vec3(0, 1, 0));
    b.instance("tree " + std::to_string(k), tree, at);
  }
}

}  // namespace

Scene make_night_street() {
  SceneBuilder b("night-street");
  Scene& s = b.scene();
  const uint32_t road = b.material("asphalt", glm::vec3(1.0f), 0.0f, 0.85f);
  tile(s.materials[road], asphalt(s), 2.0f);
  const uint32_t walk = b.matte("paving", glm::vec3(1.0f));
  tile(s.materials[walk], paving(s), 2.4f);
  const uint32_t paint = b.matte("road paint", {0.75f, 0.72f, 0.6f});
  Palette p{};
  const int32_t stone = ashlar(s);
  const glm::vec3 tints[3] = {{0.75f, 0.68f, 0.58f}, {0.6f, 0.6f, 0.62f}, {0.7f, 0.5f, 0.42f}};
  for (uint32_t k = 0; k < 3; ++k) {
    p.facade[k] = b.matte("facade " + std::to_string(k), tints[k]);
    tile(s.materials[p.facade[k]], stone, 2.0f);
  }
  p.glass = b.material("dark glass", {0.03f, 0.035f, 0.04f}, 0.0f, 0.15f);
  p.billboard = b.matte("billboard", {0.85f, 0.82f, 0.75f});
  const glm::vec3 window_light[6] = {{1.2f, 0.7f, 0.3f},  {0.6f, 0.35f, 0.15f}, {1.5f, 1.1f, 0.65f},
                                     {0.7f, 0.85f, 1.0f}, {0.2f, 0.3f, 0.7f},   {0.35f, 0.22f, 0.12f}};
  for (uint32_t k = 0; k < 6; ++k) p.lit[k] = b.emitter("window " + std::to_string(k), window_light[k]);
  const glm::vec3 neon[4] = {{4.0f, 0.3f, 0.5f}, {0.3f, 2.2f, 3.5f}, {3.5f, 1.6f, 0.2f}, {0.8f, 3.5f, 0.6f}};
  for (uint32_t k = 0; k < 4; ++k) p.neon[k] = b.emitter("neon " + std::to_string(k), neon[k]);
  const uint32_t leaf = b.material("leaf", glm::vec3(1.0f), 0.0f, 0.6f);
  s.materials[leaf].double_sided = true;
  s.materials[leaf].alpha_mode = AlphaMode::kMask;
  s.materials[leaf].base_color_texture.texture = leaf_texture(s);
  const uint32_t bark = b.matte("bark", {0.2f, 0.14f, 0.1f});

  add_street(b, road, walk, paint);
  add_buildings(b, p);
  add_trees(b, bark, leaf);
  FixtureMaterials fixtures{};
  fixtures.metal = b.material("dark metal", {0.12f, 0.12f, 0.13f}, 1.0f, 0.5f);
  fixtures.tyre = b.matte("tyre", {0.03f, 0.03f, 0.03f});
  fixtures.frame = b.matte("lantern frame", {0.02f, 0.02f, 0.02f});
  fixtures.glass = p.glass;
  fixtures.paint[0] = b.material("red paint", {0.55f, 0.04f, 0.03f}, 0.0f, 0.3f);
  fixtures.paint[1] = b.material("blue paint", {0.05f, 0.12f, 0.45f}, 0.0f, 0.3f);
  add_lights(b, fixtures);
  s.environment.map = night_sky();

  // A walk down the left sidewalk, 1 m from the facade, 2 m/s, a 2 cm bob every step (0.5 s),
  // looking down the street; it passes a lamp post at z = 2 halfway and a lantern at z = -2.5.
  auto walk_path = [](uint32_t f) {
    const float t = key_time(f);
    const glm::vec3 eye(-6.0f, 1.65f + 0.02f * std::sin(2.0f * kPi * t / 0.5f), 7.0f - 2.0f * t);
    return std::pair{eye, eye + glm::vec3(5.5f + 0.25f * t, 1.2f, -40.0f)};
  };
  b.camera(walk_path(0).first, walk_path(0).second, 0.9f);
  b.camera_path(walk_path);
  return b.finish();
}

}  // namespace strata::scene::builtin
