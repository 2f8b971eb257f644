// overlap-uv: UV parameterisations that are not one-to-one, as in the ReSTIR LoD paper's Fig. 6.
// A 4 m x 4 m floor whose left half mirrors the right half in UV (u = |x| / 2, so two sets of
// triangles share each UV region) and a 1 m cube whose six faces all map to the same [0,1]^2
// square. Each has two LoD levels built by construction: the floor 32 x 32 / 4 x 4 cells, the
// cube 8 x 8 / 2 x 2 cells per face (level 1 keeps the UV layout of level 0).
// Light: a 1 m x 1 m area light 3.5 m up (radiance 15) and a dim environment 0.05.
// Animation: the cube turns a half revolution; the camera drifts 1 m sideways; the LoD schedule
// alternates both objects' levels every 15 frames, in opposite phase.
#include <cmath>
#include <utility>

#include <glm/gtc/matrix_transform.hpp>

#include "scene/builtin/builtins.h"
#include "scene/builtin/common.h"
#include "scene/builtin/shapes.h"

namespace strata::scene::builtin {
namespace {

Primitive mirrored_floor(uint32_t cells, uint32_t material) {
  Primitive p = quad({-2.0f, 0.0f, 2.0f}, {4.0f, 0.0f, 0.0f}, {0.0f, 0.0f, -4.0f}, material, cells);
  // quad's u runs 0..1 over x in [-2, 2]; fold it so both halves cover [0, 1] (mirrored at x = 0).
  for (glm::vec2& uv : p.uvs) uv.x = std::abs(2.0f * uv.x - 1.0f);
  return p;
}

}  // namespace

Scene make_overlap_uv() {
  SceneBuilder b("overlap-uv");
  const uint32_t tile = b.material("tile", {0.6f, 0.55f, 0.5f}, 0.0f, 0.7f);
  const uint32_t paint = b.material("paint", {0.7f, 0.3f, 0.15f}, 0.0f, 0.4f);
  const uint32_t light = b.emitter("light", {15.0f, 15.0f, 15.0f});

  const uint32_t floor_fine = b.mesh("floor_lod0", {mirrored_floor(32, tile)});
  const uint32_t floor_coarse = b.mesh("floor_lod1", {mirrored_floor(4, tile)});
  const uint32_t floor = b.instance("floor", {floor_fine, floor_coarse}, glm::mat4(1.0f), 0);

  const uint32_t cube_fine = b.mesh("cube_lod0", {box(glm::vec3(0.5f), paint, 8)});
  const uint32_t cube_coarse = b.mesh("cube_lod1", {box(glm::vec3(0.5f), paint, 2)});
  const uint32_t cube = b.instance("cube", {cube_fine, cube_coarse}, glm::mat4(1.0f), 1);
  b.track(cube, [](uint32_t f) {
    TransformKey key;
    key.translation = {0.0f, 0.8f, 0.0f};
    const float angle = kPi * static_cast<float>(f) / static_cast<float>(kFrameCount - 1);
    key.rotation = glm::angleAxis(angle, glm::normalize(glm::vec3(0.3f, 1.0f, 0.2f)));
    return key;
  });
  for (uint32_t f = 0; f < kFrameCount; f += 15) {
    const uint32_t phase = (f / 15) % 2;
    b.lod_key(f, floor, phase);
    b.lod_key(f, cube, 1 - phase);
  }

  b.instance("light",
             b.mesh("light", {facing_quad({0.0f, 3.5f, 0.0f}, {0, -1, 0}, 1.0f, 1.0f, light)}));
  b.scene().environment.radiance = glm::vec3(0.05f);

  const glm::vec3 target(0.0f, 0.4f, 0.0f);
  auto drift = [&](uint32_t f) {
    const float x = -0.5f + static_cast<float>(f) / static_cast<float>(kFrameCount - 1);
    return std::pair{glm::vec3(x, 2.2f, 4.0f), target};
  };
  b.camera(drift(0).first, target, 0.8f);
  b.camera_path(drift);
  return b.finish();
}

}  // namespace strata::scene::builtin
