// lod-cliff: an 80 m x 80 m height field (160 x 160 vertices, fBm value noise) with a 14 m cliff
// across it, UV-mapped as uv = grid coords / 159, in three LoD levels from make_lod_chain (about
// 1, 1/4 and 1/16 of the 50,562 triangles; borders locked so the coarse levels keep the
// terrain's outline).
// Light: a sun, a 6 m x 6 m quad 600 m away (solid angle 1e-4 sr) of radiance ~3e4, plus a
// constant sky environment (0.35, 0.45, 0.6).
// Animation: the camera flies from 38 m to 2 m in front of the cliff; the LoD schedule switches
// the terrain from level 2 to 1 at frame 40 and to 0 at frame 80.
#include <cmath>
#include <utility>

#include "scene/builtin/builtins.h"
#include "scene/builtin/common.h"
#include "scene/builtin/random.h"
#include "scene/builtin/shapes.h"
#include "scene/lod.h"

namespace strata::scene::builtin {
namespace {

constexpr uint32_t kSeed = 0x5eedc1ffu;

float smoothstep(float e0, float e1, float x) {
  const float t = glm::clamp((x - e0) / (e1 - e0), 0.0f, 1.0f);
  return t * t * (3.0f - 2.0f * t);
}

// Value noise in [-1, 1] on the integer lattice, smoothly interpolated.
float value_noise(float x, float z, uint32_t seed) {
  const float fx = std::floor(x);
  const float fz = std::floor(z);
  const int32_t ix = static_cast<int32_t>(fx);
  const int32_t iz = static_cast<int32_t>(fz);
  const float tx = smoothstep(0.0f, 1.0f, x - fx);
  const float tz = smoothstep(0.0f, 1.0f, z - fz);
  auto corner = [&](int32_t dx, int32_t dz) {
    return static_cast<float>(hash2(ix + dx, iz + dz, seed) >> 8) * (2.0f / 16777216.0f) - 1.0f;
  };
  const float a = glm::mix(corner(0, 0), corner(1, 0), tx);
  const float b = glm::mix(corner(0, 1), corner(1, 1), tx);
  return glm::mix(a, b, tz);
}

float fbm(float x, float z) {
  float sum = 0.0f;
  float amplitude = 1.0f;
  float frequency = 1.0f / 16.0f;
  for (uint32_t octave = 0; octave < 5; ++octave) {
    sum += amplitude * value_noise(x * frequency, z * frequency, kSeed + octave);
    amplitude *= 0.5f;
    frequency *= 2.0f;
  }
  return sum;
}

float terrain_height(float x, float z) {
  // The cliff edge wanders around z = -8; behind it a plateau 14 m up, in front rolling ground.
  const float edge = -8.0f + 2.0f * value_noise(x / 10.0f, 0.5f, kSeed + 99u);
  const float cliff = 14.0f * smoothstep(edge + 1.5f, edge - 1.5f, z);
  return cliff + 2.5f * fbm(x, z);
}

}  // namespace

Scene make_lod_cliff() {
  SceneBuilder b("lod-cliff");
  const uint32_t rock = b.material("rock", {0.45f, 0.40f, 0.35f}, 0.0f, 0.9f);
  const uint32_t sun = b.emitter("sun", {32000.0f, 30000.0f, 27000.0f});

  const Primitive terrain = height_field(80.0f, 160, rock, terrain_height);
  std::vector<uint32_t> levels;
  const std::vector<Primitive> chain = make_lod_chain(terrain, 3, 0.25f, /*lock_border=*/true);
  for (size_t l = 0; l < chain.size(); ++l)
    levels.push_back(b.mesh("terrain_lod" + std::to_string(l), {chain[l]}));
  const uint32_t coarsest = static_cast<uint32_t>(levels.size() - 1);
  const uint32_t ground = b.instance("terrain", levels, glm::mat4(1.0f), coarsest);

  const glm::vec3 sun_direction = glm::normalize(glm::vec3(-0.35f, 0.55f, 0.75f));
  b.instance("sun",
             b.mesh("sun", {facing_quad(600.0f * sun_direction, -sun_direction, 6.0f, 6.0f, sun)}));
  b.scene().environment.radiance = {0.35f, 0.45f, 0.6f};

  const glm::vec3 target(0.0f, 8.0f, -12.0f);
  b.camera({0.0f, 10.0f, 38.0f}, target, 0.9f);
  b.camera_path([&](uint32_t f) {
    const float s = static_cast<float>(f) / static_cast<float>(kFrameCount - 1);
    return std::pair{glm::mix(glm::vec3(0.0f, 10.0f, 38.0f), glm::vec3(0.0f, 6.0f, 2.0f), s),
                     target};
  });
  b.lod_key(0, ground, coarsest);
  b.lod_key(40, ground, coarsest > 0 ? coarsest - 1 : 0);
  b.lod_key(80, ground, 0);
  return b.finish();
}

}  // namespace strata::scene::builtin
