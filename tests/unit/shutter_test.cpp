// The camera over an open shutter: the device's shutter_camera (include/shutter.h, compiled as C++)
// at every shutter time must be the host's interpolation between the opening and the closing
// camera (scene/shutter.h), so that the GPU moves the camera the way the frame state says.
#include <gtest/gtest.h>

#include <glm/gtc/quaternion.hpp>

#include "include/shutter.h"
#include "render/frame_constants.h"
#include "scene/shutter.h"

namespace strata {
namespace {

constexpr uint32_t k_w = 64, k_h = 48;

scene::Camera camera(glm::vec3 position, float yaw_deg, float pitch_deg, float yfov, float aperture) {
  scene::Camera c;
  c.position = position;
  c.orientation = glm::angleAxis(glm::radians(yaw_deg), glm::vec3(0, 1, 0)) * glm::angleAxis(glm::radians(pitch_deg), glm::vec3(1, 0, 0));
  c.yfov = yfov;
  c.aperture = aperture;
  c.focus_distance = 2.0f + aperture;
  return c;
}

void expect_near(glm::vec4 a, glm::vec4 b, const char* what, float t) {
  for (int i = 0; i < 4; ++i) EXPECT_NEAR(a[i], b[i], 2e-5f) << what << "[" << i << "] at t = " << t;
}

TEST(Shutter, DeviceCameraFollowsTheHostInterpolation) {
  const scene::Camera previous = camera({0.5f, 1.0f, 4.0f}, -20.0f, 5.0f, 0.9f, 0.0f);
  scene::Camera current = camera({1.5f, 1.2f, 3.0f}, 25.0f, -10.0f, 0.7f, 0.2f);
  current.shutter = 0.6f;
  scene::FrameState frame;
  frame.camera = current;
  frame.camera_open = scene::shutter_open_camera(previous, current);
  ASSERT_TRUE(frame.camera_open.has_value());
  const gpu::GpuCamera close = render::make_camera(current, k_w, k_h);
  const gpu::GpuShutter shutter = render::make_shutter(frame);
  for (float t : {0.0f, 0.25f, 0.5f, 0.8f, 0.999f}) {
    const scene::Camera host = scene::interpolate_camera(*frame.camera_open, current, t);
    gpu::GpuCamera want = render::make_camera(host, k_w, k_h);
    want.position = glm::vec4(host.position - current.position, 0.0f);
    const gpu::GpuCamera got = gpu::shutter_camera(close, shutter, t);
    expect_near(got.forward, want.forward, "forward", t);
    expect_near(got.right, want.right, "right", t);
    expect_near(got.up, want.up, "up", t);
    expect_near(got.lens, want.lens, "lens", t);
    expect_near(got.position, want.position, "position", t);
  }
}

TEST(Shutter, OpensOnTheWayFromThePreviousCamera) {
  const scene::Camera previous = camera({0, 0, 5}, 0.0f, 0.0f, 0.8f, 0.0f);
  scene::Camera current = camera({2, 0, 5}, 0.0f, 0.0f, 0.8f, 0.0f);
  EXPECT_FALSE(scene::shutter_open_camera(previous, current).has_value()) << "a closed shutter is an instant";
  current.shutter = 0.25f;
  const auto open = scene::shutter_open_camera(previous, current);
  ASSERT_TRUE(open.has_value());
  EXPECT_NEAR(open->position.x, 1.5f, 1e-6f);  // a quarter of the frame interval before the instant
  scene::Camera still = previous;
  still.shutter = 0.25f;
  EXPECT_FALSE(scene::shutter_open_camera(previous, still).has_value()) << "nothing moves over the shutter";
  // Without motion the device camera is the frame's camera at every time.
  scene::FrameState frame;
  frame.camera = still;
  const gpu::GpuCamera close = render::make_camera(still, k_w, k_h);
  const gpu::GpuCamera at = gpu::shutter_camera(close, render::make_shutter(frame), 0.3f);
  expect_near(at.forward, close.forward, "forward", 0.3f);
  expect_near(at.position, close.position, "position", 0.3f);
}

}  // namespace
}  // namespace strata
