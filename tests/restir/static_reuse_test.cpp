// In a static scene rendered again and again with the same frame index (so the same camera samples:
// restir-gather's domains start at the primary vertex of the pixel's camera sample of the frame,
// docs/ARCHITECTURE.md), a temporal shift maps a pixel's history into the same pixel of an
// identical frame: it is the identity, so no shift may fail. A false failure is not harmless: the canonical
// sample the history cannot take gets MIS weight 1 while the history keeps its share, and when the
// same path comes back as history it fails again and the pixel goes dark for as long as its
// confidence lasts. This happened to 0.5-1% of the pixels of the Cornell box per frame, where
// reconnection rays hit x_k's own rotated box just short of it (restir/path_space.glsl,
// reconnection_visible).
#include "gpu/gpu_context.h"
#include "render/renderer.h"
#include "scene/scene_io.h"
#include "support/test_scenes.h"

namespace strata::test {
namespace {

class StaticReuse : public GpuTest {};

TEST_F(StaticReuse, TemporalShiftsOfAStaticSceneNeverFail) {
  scene::Scene s = scene::builtin_scene("cornell");
  render::RenderSettings rs;
  rs.width = 64;
  rs.height = 64;
  rs.method = "restir-gather";
  rs.max_depth = 6;
  rs.restir.spatial = false;
  rs.restir.confidence_cap = 20.0f;
  render::Renderer renderer(gpu_context(), s, rs);
  uint64_t shifts = 0, failed = 0;
  for (uint32_t f = 0; f < 4; ++f) {
    const render::FrameResult r = renderer.render(s.frame_state(0), 0);
    for (const auto& [reason, n] : r.stats.shift_failures)
      if (reason.rfind("temporal.", 0) == 0) {
        failed += n;
        if (n > 0) ADD_FAILURE() << "frame " << f << ": " << n << " shifts failed as " << reason;
      }
    if (auto it = r.stats.reuse.find("temporal.shifts"); it != r.stats.reuse.end()) shifts += it->second;
  }
  EXPECT_GT(shifts, 3u * 64u * 64u) << "every frame after the first shifts (both ways) in most pixels";
  EXPECT_EQ(failed, 0u);
}

}  // namespace
}  // namespace strata::test
