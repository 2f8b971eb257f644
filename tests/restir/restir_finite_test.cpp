// docs/ARCHITECTURE.md, Robustness for the ReSTIR methods: on every built-in scene (including `stiff`, with
// radiance 1e6 beside a near-specular floor), over a few frames of its animation, no pixel is
// NaN or Inf and every guard that rejected something counted it in the frame statistics. Frames 2
// and 3 open the shutter fully (motion blur from the previous frame's camera; the splat methods
// splat into 2 time partitions), so sharp frames, blurred ones and the change between them are covered.
// No pixel is negative either, except that the gather methods' colour control variate may take a
// channel below 0 (docs/ARCHITECTURE.md, "The colour control variate"): it keeps the pixel's
// luminance, which stays >= 0.
#include <cmath>
#include <cstdio>

#include "gpu/gpu_context.h"
#include "material/bsdf.h"
#include "render/method_table.h"
#include "render/renderer.h"
#include "scene/scene_io.h"
#include "scene/shutter.h"

namespace strata::test {
namespace {

class RestirFinite : public GpuTest, public ::testing::WithParamInterface<std::string> {};

TEST_P(RestirFinite, EveryPixelOfEveryFrameIsFinite) {
  scene::Scene s = scene::builtin_scene(GetParam());
  // restir-di runs with the biased temporal option (the DI tutorial's merge and validation), so
  // both temporal weightings are covered.
  for (const char* method : {"restir-gather", "restir-di", "restir-splat", "restir-splat-backup", "restir-multilayer"}) {
    render::RenderSettings rs;
    rs.restir.unbiased = std::string(method) == "restir-gather";
    rs.width = 16;
    rs.height = 12;
    rs.method = method;
    rs.max_depth = 8;
    rs.restir.spatial_neighbors = 2;
    rs.restir.spatial_radius = 5.0f;
    rs.restir.splats_per_frame = 2;
    render::Renderer renderer(gpu_context(), s, rs);
    uint64_t rejected = 0;
    for (uint32_t f = 0; f < 4; ++f) {
      scene::FrameState state = s.frame_state(f * 3);
      if (f >= 2) {
        state.camera.shutter = 1.0f;
        state.camera_open = scene::shutter_open_camera(s.frame_state((f - 1) * 3).camera, state.camera);
      }
      auto r = renderer.render(state, f);
      const bool colour_cv = rs.restir.colour_cv_used(render::method_spec(method, "method")) > 0.0f;
      const auto& px = r.image.rgba;
      for (size_t i = 0; i < px.size(); i += 4) {
        for (size_t c = 0; c < 4; ++c)
          ASSERT_TRUE(std::isfinite(px[i + c]) && (colour_cv || px[i + c] >= 0.0f)) << GetParam() << " " << method << " frame " << f;
        const float lum = gpu::luminance(glm::vec3(px[i], px[i + 1], px[i + 2]));
        ASSERT_GE(lum, -1e-5f * (std::abs(px[i]) + std::abs(px[i + 1]) + std::abs(px[i + 2])))
            << GetParam() << " " << method << " frame " << f << " pixel " << i / 4;
      }
      rejected += r.stats.nonfinite_rejected;
      if (f > 0) {
        EXPECT_GT(r.stats.reuse.at("temporal.shifts"), 0u) << GetParam() << " " << method;
      }
    }
    std::printf("%s %s: non-finite weights rejected and counted: %llu\n", GetParam().c_str(), method,
                static_cast<unsigned long long>(rejected));
  }
}

INSTANTIATE_TEST_SUITE_P(Builtins, RestirFinite, ::testing::ValuesIn(scene::builtin_scene_names()), scene_param_name);

}  // namespace
}  // namespace strata::test
