// The still confidence cap (docs/ARCHITECTURE.md, "Confidence cap") applies only where nothing
// moved: the camera is the previous frame's and no instance changed. A still surface does not
// qualify while another object moves (its shadows and reflections change the surface's light), so
// with a still camera and the short box sliding, still_confidence_cap must not change a single
// pixel; with nothing moving it must (else these comparisons could not tell the caps apart).
#include "gpu/gpu_context.h"
#include "render/renderer.h"
#include "scene/scene_io.h"
#include "support/test_scenes.h"

#include <glm/gtc/matrix_transform.hpp>

namespace strata::test {
namespace {

// Cornell from its own camera; with `slide`, the short box moves 5 cm along z every frame.
scene::FrameState state(const scene::Scene& s, uint32_t f, bool slide) {
  scene::FrameState st = s.frame_state(0);
  if (slide) {
    const uint32_t box = instance_named(s, "short_box");
    st.transforms[box] = glm::translate(glm::mat4(1.0f), {0.0f, 0.0f, 0.05f * float(f)}) * st.transforms[box];
  }
  return st;
}

// Frame 5's image with temporal and spatial reuse: by then a history capped at 8 and one capped at
// 2 have weighted their samples differently.
image::Image render_frames(const scene::Scene& s, const std::string& method, float still_cap, bool slide) {
  render::RenderSettings rs;
  rs.width = 24;
  rs.height = 24;
  rs.method = method;
  rs.max_depth = 4;
  rs.restir.confidence_cap = 2.0f;
  rs.restir.still_confidence_cap = still_cap;
  render::Renderer renderer(gpu_context(), s, rs);
  render::FrameResult r;
  for (uint32_t f = 0; f < 6; ++f) r = renderer.render(state(s, f, slide), f);
  return r.image;
}

size_t differing_pixels(const image::Image& a, const image::Image& b) {
  size_t n = 0;
  for (size_t i = 0; i < a.rgba.size(); i += 4)
    if (a.rgba[i] != b.rgba[i] || a.rgba[i + 1] != b.rgba[i + 1] || a.rgba[i + 2] != b.rgba[i + 2]) ++n;
  return n;
}

class StillCap : public GpuTest, public ::testing::WithParamInterface<std::string> {};

TEST_P(StillCap, AppliesOnlyWhereNothingMoved) {
  const scene::Scene s = scene::builtin_scene("cornell");
  const size_t pixels = 24 * 24;
  // Nothing moves: the still cap is the cap of every pixel, and 8 against 2 shows in most of them.
  EXPECT_GT(differing_pixels(render_frames(s, GetParam(), 8.0f, false), render_frames(s, GetParam(), 2.0f, false)),
            pixels / 4);
  // The box slides under a still camera: every pixel takes confidence_cap, the walls and the
  // floor included, so the still cap changes nothing (bit-identical images).
  EXPECT_EQ(differing_pixels(render_frames(s, GetParam(), 8.0f, true), render_frames(s, GetParam(), 2.0f, true)), 0u);
}

INSTANTIATE_TEST_SUITE_P(Methods, StillCap, ::testing::Values("restir-gather", "restir-splat"),
                         [](const ::testing::TestParamInfo<std::string>& p) { return method_test_name(p.param); });

}  // namespace
}  // namespace strata::test
