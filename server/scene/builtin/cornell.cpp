// The Cornell box (the default scene), scaled from the classic 5.56 m measurement to a 2 m box:
// x in [-1, 1], y in [0, 2], z in [-1, 1], open towards +z where the camera stands. Matte
// Lambert everywhere (metallic 0, KHR_materials_specular factor 0: no highlight), reflectances of
// the classic data set.
// Light: a 0.47 m x 0.38 m quad (the classic 130 x 105 mm opening, scaled) 1 cm below the
// ceiling, emitting radiance (17, 12, 4) downwards from its front face only.
// Animation: none (a still camera keyed at the first and last of 120 frames).
#include <cmath>

#include <glm/gtc/matrix_transform.hpp>

#include "scene/builtin/builtins.h"
#include "scene/builtin/common.h"
#include "scene/builtin/shapes.h"

namespace strata::scene::builtin {

Scene make_cornell() {
  SceneBuilder b("cornell");
  const uint32_t white = b.matte("white", {0.73f, 0.73f, 0.73f});
  const uint32_t red = b.matte("red", {0.63f, 0.065f, 0.05f});
  const uint32_t green = b.matte("green", {0.14f, 0.45f, 0.091f});
  const uint32_t light = b.emitter("light", {17.0f, 12.0f, 4.0f});

  b.instance("room", b.mesh("room", cornell_walls(white, red, green)));

  const uint32_t tall = b.mesh("tall_box", {box({0.3f, 0.6f, 0.3f}, white)});
  const uint32_t short_box = b.mesh("short_box", {box({0.3f, 0.3f, 0.3f}, white)});
  const glm::vec3 up(0.0f, 1.0f, 0.0f);
  b.instance("tall_box", tall,
             glm::rotate(glm::translate(glm::mat4(1.0f), {-0.35f, 0.6f, -0.35f}),
                         glm::radians(17.0f), up));
  b.instance(
      "short_box", short_box,
      glm::rotate(glm::translate(glm::mat4(1.0f), {0.35f, 0.3f, 0.3f}), glm::radians(-17.0f), up));

  const uint32_t lamp =
      b.mesh("light", {facing_quad({0.0f, 1.99f, 0.0f}, -up, 0.47f, 0.38f, light)});
  b.instance("light", lamp);

  // yfov 0.69 rad (39.5 degrees) frames the 2 m opening from 3.8 m.
  b.camera({0.0f, 1.0f, 3.8f}, {0.0f, 1.0f, 0.0f}, 0.69f);
  b.still_camera();
  return b.finish();
}

}  // namespace strata::scene::builtin
