// The gather methods' domains start at the pixel's primary vertex of the frame (docs/ARCHITECTURE.md,
// "Domains and their primary vertex"): a shift into a domain starts its offset path at the
// visibility buffer's hit and traces no camera ray, where a splat method's shift traces the sample's
// camera ray. With the pure reconnection shift on the Lambertian Cornell box every successful
// spatial shift is one reconnection ray (a blocked one is traced once more for its closest hit,
// restir/path_space.glsl), plus one camera ray per shift when the camera sample is the sample's.
// Unbiasedness of the fixed primary vertex is tests/restir/restir_unbiased_test.cpp's.
#include "gpu/gpu_context.h"
#include "render/renderer.h"
#include "scene/scene_io.h"
#include "support/test_scenes.h"

namespace strata::test {
namespace {

class FixedPrimary : public GpuTest {};

struct SpatialRays {
  uint64_t rays = 0;
  uint64_t shifts = 0;
  double per_shift() const { return shifts ? double(rays) / double(shifts) : 0.0; }
};

SpatialRays spatial_rays(const std::string& method) {
  scene::Scene s = scene::builtin_scene("cornell");
  render::RenderSettings rs;
  rs.width = 48;
  rs.height = 48;
  rs.method = method;
  rs.max_depth = 4;
  rs.restir.shift = render::Shift::reconnection;
  rs.restir.temporal = false;
  rs.restir.spatial_neighbors = 2;
  render::Renderer renderer(gpu_context(), s, rs);
  SpatialRays out;
  for (uint32_t f = 0; f < 2; ++f) {
    const render::FrameResult r = renderer.render(s.frame_state(f), f);
    out.rays += r.stats.rays_traced.at("spatial");
    out.shifts += r.stats.reuse.at("spatial.shifts");
  }
  return out;
}

TEST_F(FixedPrimary, GatherShiftsTraceNoCameraRay) {
  const SpatialRays gather = spatial_rays("restir-gather");
  const SpatialRays splat = spatial_rays("restir-splat");
  ASSERT_GT(gather.shifts, 2u * 48u * 48u) << "most pixels shift two neighbours and back";
  ASSERT_GT(splat.shifts, 2u * 48u * 48u);
  // At most one reconnection ray and one retrace per shift, and most shifts are not blocked.
  EXPECT_LT(gather.per_shift(), 1.5) << gather.rays << " rays for " << gather.shifts << " shifts";
  // The same shifts with a camera ray each.
  EXPECT_GT(splat.per_shift(), gather.per_shift() + 0.8) << splat.rays << " rays for " << splat.shifts << " shifts";
}

TEST_F(FixedPrimary, PrimaryDecisionSaysWhatTheBufferHolds) {
  scene::Scene s = scene::builtin_scene("cornell");
  for (const char* method : {"restir-gather", "restir-splat"}) {
    render::RenderSettings rs;
    rs.width = 16;
    rs.height = 16;
    rs.method = method;
    render::Renderer renderer(gpu_context(), s, rs);
    const render::FrameResult r = renderer.render(s.frame_state(0), 0);
    bool found = false;
    for (const auto& d : r.stats.passes)
      if (d.pass == "primary") {
        found = true;
        EXPECT_TRUE(d.ran);
        const bool fixed = std::string(method) == "restir-gather";
        EXPECT_EQ(d.reason.find("primary vertex") != std::string::npos, fixed) << method << ": " << d.reason;
      }
    EXPECT_TRUE(found) << method;
  }
}

}  // namespace
}  // namespace strata::test
