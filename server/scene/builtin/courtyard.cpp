// courtyard: game content in one small animated scene, every feature of the scene bridge at once.
// A paved ground (sRGB base colour and metallic-roughness textures, repeated 8 x 8 by
// KHR_texture_transform: stones of 0.5 m) meets two brick walls (a base colour texture); a shrub
// of 24 alpha-masked leaf cards (MASK at 0.5, double-sided) sways; a sign on the back wall emits
// through an emissive texture (a textured emitter: light sampling selects its triangles by their
// integrated texture). Light: three KHR_lights_punctual lights (a lantern circling the shrub, a
// spot on the sign's wall, a low directional sun) and an equirectangular sky (a generated 64 x 32
// HDR image, brighter towards the sun), at dusk levels, so that the sign and the lantern matter.
// The camera dollies along the side wall. Every texture is generated here (deterministic), 64 x 64
// texels or smaller.
#include <algorithm>
#include <cmath>
#include <string>

#include <glm/gtc/matrix_transform.hpp>

#include "scene/builtin/builtins.h"
#include "scene/builtin/common.h"
#include "scene/builtin/random.h"
#include "scene/builtin/shapes.h"
#include "scene/builtin/textures.h"
#include "scene/environment_map.h"

namespace strata::scene::builtin {
namespace {

// Paving: 4 x 4 stones of 16 texels with 2-texel grout; each stone its own shade (base colour) and
// roughness (metallic-roughness G; grout rough).
void pave(Scene& s, Material& m) {
  Pcg32 rng(0x9a7e5u);
  float shade[16], rough[16];
  for (int k = 0; k < 16; ++k) {
    shade[k] = rng.uniform(0.75f, 1.0f);
    rough[k] = rng.uniform(0.45f, 0.85f);
  }
  auto grout = [](uint32_t x, uint32_t y) { return x % 16 < 2 || y % 16 < 2; };
  m.base_color_texture.texture = add_generated(s, "paving", 64, 64, ColorSpace::kSrgb, [&](uint32_t x, uint32_t y) {
    const float v = grout(x, y) ? 0.35f : shade[(y / 16) * 4 + x / 16];
    return rgba(0.62f * v, 0.58f * v, 0.52f * v);
  });
  m.metallic_roughness_texture.texture = add_generated(s, "paving-roughness", 64, 64, ColorSpace::kLinear, [&](uint32_t x, uint32_t y) {
    return rgba(0.0f, grout(x, y) ? 1.0f : rough[(y / 16) * 4 + x / 16], 0.0f);
  });
  m.base_color_texture.transform.scale = glm::vec2(8.0f);
  m.metallic_roughness_texture.transform.scale = glm::vec2(8.0f);
}

// Bricks: 4 courses of 2 bricks (32 x 16 texels, 2-texel mortar), every other course offset by half
// a brick.
void brick(Scene& s, Material& m) {
  Pcg32 rng(0xb21c4u);
  float shade[8];
  for (float& v : shade) v = rng.uniform(0.7f, 1.0f);
  m.base_color_texture.texture = add_generated(s, "bricks", 64, 64, ColorSpace::kSrgb, [&](uint32_t x, uint32_t y) {
    const uint32_t course = y / 16, shifted = (x + (course % 2) * 16) % 64;
    if (y % 16 < 2 || shifted % 32 < 2) return rgba(0.55f, 0.53f, 0.5f);
    const float v = shade[course * 2 + shifted / 32];
    return rgba(0.6f * v, 0.25f * v, 0.18f * v);
  });
  m.base_color_texture.transform.scale = glm::vec2(3.0f, 1.5f);
}

// The sign's emission: three warm bars on black (32 x 16 texels).
int32_t sign_texture(Scene& s) {
  return add_generated(s, "sign", 32, 16, ColorSpace::kSrgb, [](uint32_t x, uint32_t y) {
    const bool bar = y >= 4 && y < 12 && x >= 3 && x < 29 && (x - 3) % 9 < 6;
    return bar ? rgba(1.0f, 0.62f, 0.25f) : rgba(0.02f, 0.02f, 0.02f);
  });
}

// Dusk: a sky from an orange horizon to a deep blue zenith, brighter towards the sun's azimuth
// (u = 0.75, +X), a dim ground below the horizon.
EnvironmentMap dusk_sky() {
  EnvironmentMap m;
  m.name = "courtyard dusk (generated)";
  m.width = 64;
  m.height = 32;
  for (uint32_t y = 0; y < m.height; ++y) {
    const float elevation = 0.5f * kPi - (float(y) + 0.5f) / float(m.height) * kPi;
    for (uint32_t x = 0; x < m.width; ++x) {
      if (elevation < 0.0f) {
        m.radiance.emplace_back(0.08f, 0.06f, 0.05f);  // dim ground beyond the paving
        continue;
      }
      const float azimuth = (float(x) + 0.5f) / float(m.width) * 2.0f * kPi;
      const float toward_sun = 0.5f + 0.5f * std::cos(azimuth - 1.5f * kPi);
      const float h = std::exp(-4.0f * elevation);  // 1 at the horizon
      const glm::vec3 zenith(0.05f, 0.08f, 0.2f), horizon(0.9f, 0.45f, 0.2f);
      m.radiance.push_back((zenith + (horizon - zenith) * h) * (0.6f + 1.4f * toward_sun * h));
    }
  }
  build_environment_tables(m);
  return m;
}

}  // namespace

Scene make_courtyard() {
  SceneBuilder b("courtyard");
  Scene& s = b.scene();
  const uint32_t ground = b.material("paving", glm::vec3(1.0f), 0.0f, 1.0f);
  pave(s, s.materials[ground]);
  const uint32_t wall = b.matte("brick", glm::vec3(1.0f));
  brick(s, s.materials[wall]);
  const uint32_t leaf = b.material("leaf", glm::vec3(1.0f), 0.0f, 0.6f);
  s.materials[leaf].double_sided = true;
  s.materials[leaf].alpha_mode = AlphaMode::kMask;
  s.materials[leaf].base_color_texture.texture = leaf_texture(s);
  const uint32_t sign = b.emitter("sign", glm::vec3(12.0f));
  s.materials[sign].emissive_texture.texture = sign_texture(s);
  const uint32_t trunk = b.material("trunk", {0.25f, 0.16f, 0.1f}, 0.0f, 0.8f);

  b.instance("ground", b.mesh("ground", {quad({-8, 0, 8}, {16, 0, 0}, {0, 0, -16}, ground)}));
  b.instance("back wall", b.mesh("back wall", {quad({-4, 0, -4}, {8, 0, 0}, {0, 3, 0}, wall)}));
  b.instance("side wall", b.mesh("side wall", {quad({-4, 0, 4}, {0, 0, -8}, {0, 3, 0}, wall)}));
  b.instance("sign", b.mesh("sign", {facing_quad({0.5f, 2.0f, -3.98f}, {0, 0, 1}, 1.2f, 0.6f, sign)}));

  // The shrub: a trunk and 24 leaf cards around it at three heights, 0.5 m square.
  Primitive cards;
  cards.material = leaf;
  Pcg32 rng(0x5b2u);
  for (uint32_t k = 0; k < 24; ++k) {
    const float angle = float(k) * 2.0f * kPi / 8.0f + 0.3f * float(k / 8), y = 0.6f + 0.35f * float(k / 8);
    const float tilt = rng.uniform(-0.4f, 0.4f);
    const glm::vec3 out(std::cos(angle), 0.0f, std::sin(angle));
    const glm::vec3 u = 0.5f * glm::vec3(-out.z, 0.0f, out.x);
    const glm::vec3 v = 0.5f * glm::normalize(glm::vec3(0.0f, 1.0f, 0.0f) + tilt * out);
    append(cards, quad(0.25f * out + glm::vec3(0.0f, y, 0.0f) - 0.5f * u, u, v, leaf));
  }
  Primitive stem = cylinder(0.05f, 1.2f, 8, trunk);
  const uint32_t shrub = b.instance("shrub", b.mesh("shrub", {stem, cards}), glm::translate(glm::mat4(1.0f), {-1.0f, 0.0f, -1.5f}));
  b.track(shrub, [](uint32_t f) {
    TransformKey k;
    k.translation = {-1.0f, 0.0f, -1.5f};
    k.rotation = glm::angleAxis(0.12f * std::sin(2.0f * kPi * float(f) / 40.0f), glm::vec3(0.0f, 0.0f, 1.0f));
    return k;
  });

  // The lantern circles the shrub at 1.4 m, 0.9 m from its stem.
  s.lights.push_back(light_at("lantern", LightType::kPoint, {1.0f, 0.75f, 0.45f}, 3.0f, glm::vec3(0.0f), {0, 0, -1}));
  LightTrack lantern{0, {}};
  for (uint32_t f = 0; f < kFrameCount; ++f) {
    const float a = 2.0f * kPi * float(f) / float(kFrameCount);
    TransformKey k;
    k.time = key_time(f);
    k.translation = glm::vec3(-1.0f + 0.9f * std::cos(a), 1.4f, -1.5f + 0.9f * std::sin(a));
    lantern.keys.push_back(k);
  }
  s.lights[0].transform = compose_key(lantern.keys.front());
  s.animation.light_tracks.push_back(lantern);
  // A spot above the sign, aimed down the back wall, cones 25 and 40 degrees.
  Light spot = light_at("wall spot", LightType::kSpot, {0.9f, 0.95f, 1.0f}, 8.0f, {2.2f, 2.8f, -3.6f}, {-0.2f, -2.8f, 0.4f});
  spot.inner_cone = glm::radians(25.0f);
  spot.outer_cone = glm::radians(40.0f);
  spot.range = 6.0f;
  s.lights.push_back(spot);
  // A low sun from +X (the sky's bright side), over the side wall's far end.
  s.lights.push_back(light_at("sun", LightType::kDirectional, {1.0f, 0.7f, 0.45f}, 1.5f, glm::vec3(0.0f), {-1.0f, -0.35f, -0.2f}));
  s.environment.map = dusk_sky();

  auto dolly = [](uint32_t f) {
    const float t = float(f) / float(kFrameCount - 1);
    const glm::vec3 eye(-2.8f + 1.6f * t, 1.6f, 3.6f);
    return std::pair{eye, glm::vec3(0.2f, 1.0f, -3.0f)};
  };
  b.camera(dolly(0).first, dolly(0).second, 0.9f);
  b.camera_path(dolly);
  return b.finish();
}

}  // namespace strata::scene::builtin
