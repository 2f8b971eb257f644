// The unbiasedness harness itself: an unbiased method (the path tracer with other seeds) passes it,
// and a 3% bias in the same method is detected. Every ReSTIR method reuses this harness.
#include <cstdio>

#include "gpu/gpu_context.h"
#include "render/renderer.h"
#include "scene/scene_io.h"
#include "support/unbiasedness.h"

namespace strata::test {
namespace {

class Unbiasedness : public GpuTest {};

RunningImage runs_of(const scene::Scene& s, uint32_t runs, uint32_t spp, uint32_t seed_base, float scale) {
  render::RenderSettings rs;
  rs.width = 16;
  rs.height = 16;
  rs.spp = spp;
  RunningImage out(rs.width, rs.height);
  for (uint32_t r = 0; r < runs; ++r) {
    rs.seed = seed_base + r;
    render::Renderer renderer(gpu_context(), s, rs);
    auto img = renderer.render(s.frame_state(0), 0).image;
    for (float& v : img.rgba) v *= scale;
    out.add(img);
  }
  return out;
}

TEST_F(Unbiasedness, PathTracerAgainstItsReferencePassesAndABiasIsCaught) {
  scene::Scene s = scene::builtin_scene("cornell");
  RunningImage reference = runs_of(s, 16, 1024, 1000, 1.0f);
  RunningImage unbiased = runs_of(s, 32, 64, 2000, 1.0f);
  BiasReport ok = compare_to_reference(unbiased, reference, 4);
  EXPECT_TRUE(ok.passed) << ok.describe();
  std::printf("unbiased: %s\n", ok.describe().c_str());
  RunningImage biased = runs_of(s, 32, 64, 2000, 1.03f);
  BiasReport bad = compare_to_reference(biased, reference, 4);
  EXPECT_FALSE(bad.passed) << "a 3% bias went unnoticed: " << bad.describe();
  EXPECT_NEAR(bad.relative_bias, 0.03, 0.01);
  std::printf("biased by 3%%: %s\n", bad.describe().c_str());
}

TEST(UnbiasednessMath, InverseNormalCdf) {
  EXPECT_NEAR(inverse_normal_cdf(0.5), 0.0, 1e-9);
  EXPECT_NEAR(inverse_normal_cdf(0.975), 1.959964, 1e-5);
  EXPECT_NEAR(inverse_normal_cdf(1.0 - 1e-6), 4.753424, 1e-5);
}

}  // namespace
}  // namespace strata::test
