// Every built-in scene renders on lavapipe without a single non-finite sample, with statistics that
// add up, over a few animation frames (camera motion, object motion, LoD switches).
#include <cmath>

#include "gpu/gpu_context.h"
#include "render/renderer.h"
#include "scene/scene_io.h"

namespace strata::test {
namespace {

class BuiltinRender : public GpuTest, public ::testing::WithParamInterface<std::string> {};

TEST_P(BuiltinRender, NoNanOrInfAndConsistentStatistics) {
  scene::Scene s = scene::builtin_scene(GetParam());
  render::RenderSettings rs;
  rs.width = 32;
  rs.height = 24;
  rs.spp = 4;
  render::Renderer renderer(gpu_context(), s, rs);
  double total = 0.0;
  for (uint32_t f : {0u, 1u, 37u, 90u}) {
    auto r = renderer.render(s.frame_state(f), f);
    for (float v : r.image.rgba) ASSERT_TRUE(std::isfinite(v)) << GetParam() << " frame " << f;
    for (size_t i = 0; i < r.image.rgba.size(); i += 4) {
      ASSERT_GE(r.image.rgba[i], 0.0f);
      total += r.image.rgba[i] + r.image.rgba[i + 1] + r.image.rgba[i + 2];
    }
    EXPECT_EQ(r.stats.nonfinite_rejected, 0u) << GetParam() << " frame " << f;
    EXPECT_EQ(r.stats.paths, uint64_t(rs.width) * rs.height * rs.spp);
    EXPECT_EQ(r.stats.rays_traced.at("primary"), r.stats.paths);
    EXPECT_GT(r.stats.gpu_ms_total, 0.0);
    EXPECT_EQ(r.stats.tlas_builds + r.stats.tlas_refits, 1u);
    EXPECT_GT(r.stats.memory_bytes.at("geometry"), 0u);
  }
  EXPECT_GT(total, 0.0) << GetParam() << " rendered black";
}

INSTANTIATE_TEST_SUITE_P(BuiltinScenes, BuiltinRender, ::testing::ValuesIn(scene::builtin_scene_names()),
                         scene_param_name);

}  // namespace
}  // namespace strata::test
