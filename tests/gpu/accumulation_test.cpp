// Reference rendering accumulates samples across calls: N samples then N more of the same frame
// state equal 2N samples in one call (same random streams, same summation order), and the TLAS is
// refitted, not rebuilt, when only transforms change between frames.
#include "gpu/gpu_context.h"
#include "render/renderer.h"
#include "scene/scene_io.h"

namespace strata::test {
namespace {

class Accumulation : public GpuTest {};

TEST_F(Accumulation, TwoHalvesEqualOneWhole) {
  scene::Scene s = scene::builtin_scene("cornell");
  scene::FrameState frame = s.frame_state(0);
  render::RenderSettings rs;
  rs.width = 16;
  rs.height = 16;
  rs.spp = 32;
  render::Renderer halves(gpu_context(), s, rs);
  halves.render(frame, 5);
  auto accumulated = halves.render(frame, 5, /*accumulate=*/true);
  EXPECT_EQ(accumulated.accumulated_spp, 64u);
  rs.spp = 64;
  render::Renderer whole(gpu_context(), s, rs);
  auto one = whole.render(frame, 5);
  ASSERT_EQ(one.image.rgba.size(), accumulated.image.rgba.size());
  for (size_t i = 0; i < one.image.rgba.size(); ++i) ASSERT_FLOAT_EQ(one.image.rgba[i], accumulated.image.rgba[i]) << i;
}

TEST_F(Accumulation, TlasRefitsWhenOnlyTransformsMoveAndRebuildsOnLodSwitch) {
  scene::Scene s = scene::builtin_scene("chess");
  render::RenderSettings rs;
  rs.width = 8;
  rs.height = 8;
  render::Renderer r(gpu_context(), s, rs);
  scene::FrameState previous = s.frame_state(0);
  EXPECT_EQ(r.render(previous, 0).stats.tlas_builds, 1u);
  int refits = 0, rebuilds = 0;
  for (uint32_t f = 1; f < 40; ++f) {
    scene::FrameState frame = s.frame_state(f);
    auto stats = r.render(frame, f).stats;
    if (frame.lods == previous.lods) {
      EXPECT_EQ(stats.tlas_refits, 1u) << "frame " << f;
      ++refits;
    } else {
      EXPECT_EQ(stats.tlas_builds, 1u) << "frame " << f;
      ++rebuilds;
    }
    previous = frame;
  }
  EXPECT_GT(refits, 0);
  EXPECT_GT(rebuilds, 0) << "chess switches LoD levels every 10 frames";
}

}  // namespace
}  // namespace strata::test
