#pragma once
// The camera over an open shutter (motion blur, RS-main 4.4; RS-supp 3.3.1). A frame's camera is
// where the shutter closes, at the frame's instant; the shutter opens a fraction `shutter` of the
// frame interval earlier, on the way from the previous frame's camera. Between two cameras the
// motion is linear in position, field of view and lens, and a shortest-path slerp in orientation
// (the same interpolation the default animation uses between keys).
#include <optional>

#include "scene/scene.h"

namespace strata::scene {

// The camera a fraction t in [0, 1] of the way from a to b (the shutter of the result is b's).
Camera interpolate_camera(const Camera& a, const Camera& b, float t);

// Where the shutter of `current` opens when the frame before had camera `previous`; none when the
// shutter is closed or the camera does not move over it (the frame is then an instant).
std::optional<Camera> shutter_open_camera(const Camera& previous, const Camera& current);

}  // namespace strata::scene
