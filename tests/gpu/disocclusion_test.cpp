// Pass `disocclusion` (docs/ARCHITECTURE.md, Statistics, `disoccluded_pixels`; the mask of the masked
// metrics): a quad in front of a wall moves sideways; the wall it uncovers is disoccluded, the quad
// itself and the wall that was visible before are not; an unchanged frame has no disocclusion.
#include <glm/gtc/matrix_transform.hpp>

#include "gpu/gpu_context.h"
#include "support/test_scenes.h"
#include "render/disocclusion.h"
#include "scene/scene_io.h"

namespace strata::test {
namespace {

class Disocclusion : public GpuTest {};

scene::Mesh unit_quad() { return quad_mesh(0.5f, 0.0f, 0); }  // [-0.5, 0.5]^2 in z = 0, facing +z

// A 20 m wall at z = -2 and a 1 m quad at z = 0; the camera at (0, 0, 5) looks down -z.
scene::Scene wall_and_quad() {
  scene::Scene s;
  s.name = "wall-and-quad";
  s.materials.push_back({});
  s.meshes = {unit_quad()};
  s.instances.push_back({"wall", {0}, glm::scale(glm::translate(glm::mat4(1.0f), glm::vec3(0, 0, -2)), glm::vec3(20.0f)), 0});
  s.instances.push_back({"quad", {0}, glm::mat4(1.0f), 0});
  s.camera.position = {0.0f, 0.0f, 5.0f};
  s.validate();
  return s;
}

scene::FrameState quad_at(const scene::Scene& s, float x) {
  scene::FrameState st = s.frame_state(0);
  st.transforms[1] = glm::translate(glm::mat4(1.0f), glm::vec3(x, 0, 0));
  return st;
}

constexpr uint32_t k_size = 32;

uint8_t at(const std::vector<uint8_t>& m, uint32_t x, uint32_t y) { return m.at(size_t(y) * k_size + x); }

TEST_F(Disocclusion, UncoveredWallIsDisoccludedAndNothingElse) {
  scene::Scene s = wall_and_quad();
  render::DisocclusionMask pass(gpu_context(), s);
  // The quad moves from x = 0 to x = 1: with yfov 0.8 it spans pixels ~20..27 of 32 afterwards,
  // ~12..19 before.
  auto m = pass.compute(quad_at(s, 0.0f), quad_at(s, 1.0f), k_size, k_size);
  ASSERT_EQ(m.size(), size_t(k_size) * k_size);
  EXPECT_EQ(at(m, 15, 16), 1) << "wall behind the quad's old place";
  EXPECT_EQ(at(m, 13, 16), 1);
  EXPECT_EQ(at(m, 23, 16), 0) << "the quad itself was visible before (it moved with its transform)";
  EXPECT_EQ(at(m, 4, 16), 0) << "wall visible in both frames";
  EXPECT_EQ(at(m, 16, 2), 0) << "wall above the quad, visible in both frames";
  size_t count = 0;
  for (uint8_t v : m) count += v;
  // The uncovered strip: quad's old footprint (~7.6 px square) minus what it still covers.
  EXPECT_GT(count, 20u);
  EXPECT_LT(count, 70u);
}

TEST_F(Disocclusion, UnchangedFrameHasNone) {
  scene::Scene s = wall_and_quad();
  render::DisocclusionMask pass(gpu_context(), s);
  auto m = pass.compute(quad_at(s, 0.3f), quad_at(s, 0.3f), k_size, k_size);
  for (uint8_t v : m) ASSERT_EQ(v, 0);
}

TEST_F(Disocclusion, CarouselUncoversBackdrop) {
  scene::Scene s = scene::builtin_scene("carousel");
  render::DisocclusionMask pass(gpu_context(), s);
  auto m = pass.compute(s.frame_state(0), s.frame_state(8), k_size, k_size);
  size_t count = 0;
  for (uint8_t v : m) count += v;
  EXPECT_GT(count, 0u);
  EXPECT_LT(count, m.size() / 2);
}

}  // namespace
}  // namespace strata::test
