#include "scene/shutter.h"

#include <glm/gtc/quaternion.hpp>

namespace strata::scene {

Camera interpolate_camera(const Camera& a, const Camera& b, float t) {
  Camera c = b;
  c.position = glm::mix(a.position, b.position, t);
  c.orientation = glm::normalize(glm::slerp(a.orientation, b.orientation, t));  // shortest path
  c.yfov = glm::mix(a.yfov, b.yfov, t);
  c.aperture = glm::mix(a.aperture, b.aperture, t);
  c.focus_distance = glm::mix(a.focus_distance, b.focus_distance, t);
  return c;
}

std::optional<Camera> shutter_open_camera(const Camera& previous, const Camera& current) {
  if (!(current.shutter > 0.0f)) return std::nullopt;
  Camera still = previous;
  still.shutter = current.shutter;
  if (still == current) return std::nullopt;
  Camera open = interpolate_camera(previous, current, 1.0f - current.shutter);
  if (open == current) return std::nullopt;
  return open;
}

}  // namespace strata::scene
