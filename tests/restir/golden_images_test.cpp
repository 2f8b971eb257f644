// Every method renders the same images as the frame recorded in tests/data/golden/ for the same
// seed: a refactoring of the pipeline (stages, bindings, resolvers) must not change one bit of what
// a method computes. The golden frames are the last of four frames of a moving scene (carousel:
// objects move; cornell: the camera moves, with the shutter open on frames 2 and 3), so history,
// splatting, motion blur and spatial reuse all contribute.
//
// Bit-exactness holds on the device the frames were recorded on (lavapipe, whose LLVM code
// generation is deterministic for a given Mesa build); on another device the test is skipped,
// since its floating-point results differ by rounding. STRATA_WRITE_GOLDEN=DIR writes new frames
// into DIR instead of comparing, for a change that is meant to alter images (its commit then says
// why, and what it measured).
#include <cmath>
#include <cstdint>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <ostream>
#include <string>
#include <vector>

#include "gpu/gpu_context.h"
#include "render/renderer.h"
#include "scene/scene_io.h"
#include "scene/shutter.h"

namespace strata::test {
namespace {

struct Golden {
  std::string scene;
  std::string method;
};

void PrintTo(const Golden& g, std::ostream* os) { *os << g.scene << " / " << g.method; }

std::string file_name(const Golden& g) { return g.scene + "-" + g.method + ".f32"; }

std::vector<float> render_golden(const Golden& g) {
  scene::Scene s = scene::builtin_scene(g.scene);
  render::RenderSettings rs;
  rs.width = 32;
  rs.height = 24;
  rs.method = g.method;
  rs.max_depth = 6;
  rs.seed = 7;
  rs.restir.spatial_neighbors = 2;
  rs.restir.spatial_radius = 6.0f;
  rs.restir.splats_per_frame = 2;
  rs.restir.unbiased = g.method != "restir-di";  // restir-di: the DI tutorial's biased merge
  render::Renderer renderer(gpu_context(), s, rs);
  const bool blur = g.scene == "cornell";
  render::FrameResult r;
  for (uint32_t f = 0; f < 4; ++f) {
    scene::FrameState state = s.frame_state(f * 4);
    if (g.scene == "cornell") state.camera.position += glm::vec3(0.04f * float(f), 0.02f * float(f), -0.05f * float(f));  // a moving camera
    if (blur && f >= 2) {
      scene::FrameState before = s.frame_state((f - 1) * 4);
      before.camera.position += glm::vec3(0.04f * float(f - 1), 0.02f * float(f - 1), -0.05f * float(f - 1));
      state.camera.shutter = 1.0f;
      state.camera_open = scene::shutter_open_camera(before.camera, state.camera);
    }
    r = renderer.render(state, f);
  }
  return r.image.rgba;
}

class GoldenImages : public GpuTest, public ::testing::WithParamInterface<Golden> {};

TEST_P(GoldenImages, SameBitsAsRecorded) {
  const Golden g = GetParam();
  std::vector<float> image = render_golden(g);
  for (float v : image) ASSERT_TRUE(std::isfinite(v));
  if (const char* dir = std::getenv("STRATA_WRITE_GOLDEN")) {
    std::filesystem::create_directories(dir);
    std::ofstream out(std::filesystem::path(dir) / file_name(g), std::ios::binary);
    out.write(reinterpret_cast<const char*>(image.data()), std::streamsize(image.size() * sizeof(float)));
    ASSERT_TRUE(bool(out));
    GTEST_SKIP() << "wrote " << file_name(g);
  }
  if (gpu_context().device_name().find("llvmpipe") == std::string::npos)
    GTEST_SKIP() << "golden frames are bit-exact on lavapipe only; device is " << gpu_context().device_name();
  std::ifstream in(std::filesystem::path(STRATA_GOLDEN_DIR) / file_name(g), std::ios::binary);
  ASSERT_TRUE(bool(in)) << "missing " << file_name(g);
  std::vector<float> golden(image.size());
  in.read(reinterpret_cast<char*>(golden.data()), std::streamsize(golden.size() * sizeof(float)));
  ASSERT_EQ(size_t(in.gcount()), golden.size() * sizeof(float)) << file_name(g) << " has the wrong size";
  size_t differ = 0;
  double max_diff = 0.0;
  for (size_t i = 0; i < image.size(); ++i) {
    if (std::memcmp(&image[i], &golden[i], sizeof(float)) != 0) ++differ;
    max_diff = std::max(max_diff, double(std::fabs(image[i] - golden[i])));
  }
  EXPECT_EQ(differ, 0u) << g.scene << " " << g.method << ": " << differ << " of " << image.size()
                        << " channels differ from the recorded frame, by at most " << max_diff;
}

std::vector<Golden> all_goldens() {
  std::vector<Golden> v;
  for (const char* scene : {"carousel", "cornell"})
    for (const auto& method : render::available_methods()) v.push_back({scene, method});
  return v;
}

std::string golden_name(const ::testing::TestParamInfo<Golden>& param) {
  std::string n = param.param.scene + "_" + param.param.method;
  for (auto& ch : n)
    if (ch == '-') ch = '_';
  return n;
}

INSTANTIATE_TEST_SUITE_P(Methods, GoldenImages, ::testing::ValuesIn(all_goldens()), golden_name);

}  // namespace
}  // namespace strata::test
