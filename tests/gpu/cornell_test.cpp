// The default scene's image mean from the GPU path tracer (NEE + MIS) against the independent CPU
// estimate (BSDF sampling only, double precision). Both are unbiased estimates of the same
// integral, so their difference is normal with variance se_gpu^2 + se_cpu^2.
#include <cmath>
#include <cstdio>

#include "gpu/gpu_context.h"
#include "render/renderer.h"
#include "scene/scene_io.h"
#include "support/cpu_tracer.h"

namespace strata::test {
namespace {

class Cornell : public GpuTest {};

TEST_F(Cornell, ImageMeanMatchesIndependentCpuEstimate) {
  scene::Scene s = scene::builtin_scene("cornell");
  scene::FrameState frame = s.frame_state(0);
  const uint32_t w = 24, h = 24, max_depth = 64;
  render::RenderSettings rs;
  rs.width = w;
  rs.height = h;
  rs.spp = 1024;
  rs.max_depth = max_depth;
  rs.seed = 3;
  render::Renderer renderer(gpu_context(), s, rs);
  auto result = renderer.render(frame, 0);
  // Per-pixel means are independent; the image mean's standard error follows from their spread
  // around the per-pixel expectations, which we do not know, so use the per-pixel variance of a
  // second independent render: var(a - b) / 2 per pixel.
  rs.seed = 4;
  render::Renderer second(gpu_context(), s, rs);
  auto result2 = second.render(frame, 0);

  MeanEstimate cpu = estimate_image_mean(s, frame, w, h, 4096, 99, max_depth);
  for (int c = 0; c < 3; ++c) {
    double sum = 0.0, diff2 = 0.0;
    size_t n = size_t(w) * h;
    for (size_t i = 0; i < n; ++i) {
      double a = result.image.rgba[4 * i + size_t(c)], b = result2.image.rgba[4 * i + size_t(c)];
      sum += 0.5 * (a + b);
      diff2 += (a - b) * (a - b);
    }
    double gpu_mean = sum / double(n);
    // var of one render's image mean = sum_i var_i / n^2, var_i estimated by (a-b)^2 / 2;
    // the mean of two renders halves it.
    double gpu_se = std::sqrt(diff2 / 2.0 / double(n) / double(n) / 2.0);
    double se = std::sqrt(gpu_se * gpu_se + cpu.std_error[c] * cpu.std_error[c]);
    // 4.5 sigma: a false failure has probability < 1e-5 per channel. The CPU estimate is the
    // noisier one; the combined se is asserted small enough for the test to catch a 4% bias.
    EXPECT_NEAR(gpu_mean, cpu.mean[c], 4.5 * se) << "channel " << c;
    std::printf("cornell channel %d: gpu %.5f +- %.5f, cpu %.5f +- %.5f\n", c, gpu_mean, gpu_se, cpu.mean[c], cpu.std_error[c]);
    EXPECT_LT(4.5 * se, 0.04 * cpu.mean[c]) << "channel " << c << ": test too noisy to detect a 4% bias";
  }
  EXPECT_EQ(result.stats.nonfinite_rejected, 0u);
}

}  // namespace
}  // namespace strata::test
