// cornell-lamps: the Cornell box (cornell.cpp) lit by KHR_lights_punctual lights instead of its
// ceiling quad: a warm spot lamp under the ceiling aimed at the short box (cones 20 and 35 degrees,
// range 4 m), a small cool point light beside the tall box at 1.2 m height, and a dim directional
// light shining in through the open front from above the camera. The ceiling quad stays as a dark
// fixture (no emission).
#include <cmath>

#include "scene/builtin/builtins.h"
#include "scene/builtin/common.h"

namespace strata::scene::builtin {
Scene make_cornell_lamps() {
  Scene s = make_cornell();
  s.name = "cornell-lamps";
  for (Material& m : s.materials)
    if (m.name == "light") m.emission = glm::vec3(0.0f);

  Light spot = light_at("spot", LightType::kSpot, {1.0f, 0.85f, 0.6f}, 6.0f, {-0.3f, 1.9f, 0.2f}, {0.6f, -1.5f, 0.1f});
  spot.inner_cone = glm::radians(20.0f);
  spot.outer_cone = glm::radians(35.0f);
  spot.range = 4.0f;
  s.lights.push_back(spot);

  // A small cool point light beside the tall box (centre (-0.35, ., -0.35)).
  s.lights.push_back(light_at("bulb", LightType::kPoint, {0.6f, 0.75f, 1.0f}, 0.8f, {0.2f, 1.2f, -0.35f}, {0, 0, -1}));

  s.lights.push_back(
      light_at("sun", LightType::kDirectional, {1.0f, 0.95f, 0.9f}, 0.6f, {0.0f, 3.0f, 5.0f}, {-0.25f, -0.45f, -1.0f}));
  return s;
}

}  // namespace strata::scene::builtin
