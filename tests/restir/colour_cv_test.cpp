// The colour control variate of the gather and splat methods (docs/ARCHITECTURE.md, "The colour
// control variate"; restir_shade.comp): E = A + b (I - w lum^T) (B - A) with lum(w) = 1 keeps each
// pixel's luminance and changes only its colour; restir-multilayer does not use it and holds no
// memory for it. Its unbiasedness is tests/restir/restir_unbiased_test.cpp's (every gather and splat
// case runs with the default b, and the colour_cv_full_* cases with b = 1 everywhere).
#include <cmath>
#include <vector>

#include "gpu/gpu_context.h"
#include "material/bsdf.h"
#include "restir/colour_cv.h"
#include "render/renderer.h"
#include "scene/scene_io.h"
#include "support/test_scenes.h"

namespace strata::test {
namespace {

class ColourControlVariate : public GpuTest {};
class ColourControlVariateKeepsLuminance : public GpuTest, public ::testing::WithParamInterface<std::string> {};

struct CliffRun {
  std::vector<image::Image> frames;
  std::map<std::string, uint64_t> memory;
};

// Frames 36..39 of lod-cliff (the camera flies towards the cliff: every frame reuses history).
CliffRun render_cliff(const std::string& method, float colour_cv) {
  scene::Scene s = scene::builtin_scene("lod-cliff");
  render::RenderSettings rs;
  rs.width = 24;
  rs.height = 24;
  rs.method = method;
  rs.max_depth = 4;
  rs.restir.colour_cv = colour_cv;
  rs.restir.albedo_strata = 1;  // the albedo control variate's history would carry E into later frames
  render::Renderer renderer(gpu_context(), s, rs);
  CliffRun run;
  for (uint32_t f = 0; f < 4; ++f) run.frames.push_back(renderer.render(s.frame_state(36 + f), f).image);
  run.memory = renderer.memory_bytes();
  return run;
}

float luminance(const float* rgb) { return gpu::luminance(glm::vec3(rgb[0], rgb[1], rgb[2])); }

TEST_P(ColourControlVariateKeepsLuminance, AndChangesEachPixelsColour) {
  const CliffRun off = render_cliff(GetParam(), 0.0f);
  const CliffRun on = render_cliff(GetParam(), 0.6f);
  size_t changed = 0, pixels = 0;
  for (size_t f = 0; f < off.frames.size(); ++f) {
    const auto& a = off.frames[f].rgba;
    const auto& e = on.frames[f].rgba;
    ASSERT_EQ(a.size(), e.size());
    for (size_t i = 0; i < a.size(); i += 4) {
      // lum(E) = lum(A) up to float rounding of lum(w) = 1.
      const float la = luminance(&a[i]), le = luminance(&e[i]);
      ASSERT_NEAR(le, la, 1e-4 * std::abs(la) + 1e-6) << "frame " << f << " pixel " << i / 4;
      ++pixels;
      if (std::abs(e[i] - a[i]) > 1e-4f * std::abs(a[i]) || std::abs(e[i + 2] - a[i + 2]) > 1e-4f * std::abs(a[i + 2])) ++changed;
    }
  }
  // Frame 0 has no history, but spatial reuse moves its colour away from the initial paths' too.
  EXPECT_GT(changed, pixels / 2) << changed << " of " << pixels << " pixels changed colour";
  EXPECT_GT(on.memory.at("contribution"), off.memory.at("contribution")) << "the initial estimates and window masks";
}

INSTANTIATE_TEST_SUITE_P(Methods, ColourControlVariateKeepsLuminance, ::testing::Values("restir-gather", "restir-splat"),
                         [](const ::testing::TestParamInfo<std::string>& p) { return p.param == "restir-gather" ? "gather" : "splat"; });

// restir-multilayer's deep domains run the initial and spatial passes over the same pixels as the
// front layer, so the variate's per-pixel B and window marks would be theirs too: it leaves the
// variate out and holds no memory for it.
TEST_F(ColourControlVariate, MultilayerLeavesItOut) {
  const CliffRun off = render_cliff("restir-multilayer", 0.0f);
  const CliffRun on = render_cliff("restir-multilayer", 0.6f);
  for (size_t f = 0; f < off.frames.size(); ++f) EXPECT_EQ(off.frames[f].rgba, on.frames[f].rgba) << "frame " << f;
  EXPECT_EQ(on.memory.at("contribution"), off.memory.at("contribution"));
}

// b's shrinkage (restir/colour_cv.h) from the one-pass sums against S written out:
// n sum_j |B_j - w lum(B_j)|^2 / lum(sum_j B_j)^2.
TEST(ColourCvSpread, MatchesItsDefinitionAndShrinksB) {
  const std::vector<std::vector<glm::vec3>> windows = {
      {{1.0f, 0.5f, 0.25f}, {2.0f, 1.0f, 0.5f}, {0.1f, 0.05f, 0.025f}},                    // one colour: S = 0
      {{1.0f, 0.0f, 0.0f}, {0.0f, 1.0f, 0.0f}, {0.0f, 0.0f, 1.0f}, {0.3f, 0.3f, 0.3f}},  // saturated, spread
      {{0.8f, 0.7f, 0.6f}, {0.75f, 0.7f, 0.65f}, {0.7f, 0.7f, 0.7f}, {0.85f, 0.7f, 0.55f}, {30.0f, 28.0f, 26.0f}},
  };
  std::vector<float> spreads;
  for (const auto& bs : windows) {
    gpu::ColourWindow c = gpu::colour_window_empty();
    glm::vec3 sum(0.0f);
    for (const glm::vec3& b : bs) {
      gpu::colour_window_add(c, b);
      sum += b;
    }
    const float y = gpu::luminance(sum);
    const glm::vec3 w = sum / y;
    double direct = 0.0;
    for (const glm::vec3& b : bs) {
      const glm::vec3 d = b - w * gpu::luminance(b);
      direct += glm::dot(d, d);
    }
    direct *= double(bs.size()) / (double(y) * y);
    const float spread = gpu::colour_window_spread(c, c.sum / gpu::luminance(c.sum), gpu::luminance(c.sum));
    EXPECT_NEAR(spread, direct, 1e-4 * direct + 1e-6);
    spreads.push_back(spread);
  }
  EXPECT_NEAR(spreads[0], 0.0f, 1e-6f);
  EXPECT_GT(spreads[1], 1.0f);  // red, green and blue pixels: B's colour is mostly noise
  // b = colour_cv where the colours agree, less where they spread, never below 0.
  EXPECT_NEAR(gpu::colour_cv_b(0.6f, 0.3f, spreads[0]), 0.6f, 1e-5f);
  EXPECT_LT(gpu::colour_cv_b(0.6f, 0.3f, spreads[1]), 0.3f * 0.6f);
  EXPECT_GT(gpu::colour_cv_b(0.6f, 0.3f, spreads[2]), gpu::colour_cv_b(0.6f, 0.3f, spreads[1]));
  EXPECT_EQ(gpu::colour_cv_b(0.0f, 0.3f, spreads[1]), 0.0f);
  EXPECT_EQ(gpu::colour_cv_b(0.6f, 0.0f, spreads[1]), 0.6f);  // k = 0: no shrinkage
}

}  // namespace
}  // namespace strata::test
