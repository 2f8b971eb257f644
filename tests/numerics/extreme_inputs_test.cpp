// The stiff/extreme suite (docs/ARCHITECTURE.md, Robustness) for what exists today (the path tracer): mirrored
// geometry keeps glTF's front faces, degenerate triangles and extreme image shapes stay finite,
// LoD switching every frame and teleporting cameras never produce a non-finite sample.
#include <cmath>

#include <glm/gtc/matrix_transform.hpp>

#include "gpu/gpu_context.h"
#include "render/renderer.h"
#include "scene/scene_io.h"
#include "support/test_scenes.h"

namespace strata::test {
namespace {

class Extreme : public GpuTest {};

double mean_channel(const image::Image& img, int c) {
  double s = 0.0;
  for (size_t i = 0; i < size_t(img.width) * img.height; ++i) s += img.rgba[4 * i + size_t(c)];
  return s / double(size_t(img.width) * img.height);
}

void expect_finite(const render::FrameResult& r, const std::string& what) {
  for (float v : r.image.rgba) ASSERT_TRUE(std::isfinite(v)) << what;
  EXPECT_EQ(r.stats.nonfinite_rejected, 0u) << what;
}

// glTF: a node whose transform has a negative determinant flips the winding that counts as front.
// A furnace box mirrored in x must still emit inwards: radiance Le / (1 - albedo) = 2.
TEST_F(Extreme, MirroredFurnaceStillEmitsFromItsFrontFaces) {
  scene::Scene s = furnace_box(0.5f, 1.0f);
  s.instances[0].transform = glm::scale(glm::mat4(1.0f), glm::vec3(-1.0f, 1.0f, 1.0f));
  render::RenderSettings rs;
  rs.width = 16;
  rs.height = 16;
  rs.spp = 64;
  rs.max_depth = 128;
  render::Renderer r(gpu_context(), s, rs);
  auto result = r.render(s.frame_state(0), 0);
  expect_finite(result, "mirrored furnace");
  // Without the re-winding NEE sees every wall from behind and the mean falls to ~1.66. The image
  // mean's standard error at 16x16x64 samples is ~0.006, so 0.03 is 5 sigma.
  EXPECT_NEAR(mean_channel(result.image, 0), 2.0, 0.03);
}

TEST_F(Extreme, DegenerateTrianglesStayFinite) {
  scene::Scene s = furnace_box(0.5f, 1.0f);
  scene::Primitive degenerate;
  degenerate.positions = {{0, 0, -0.5f}, {0, 0, -0.5f}, {0.1f, 0, -0.5f}, {0.2f, 0.2f, -0.5f}, {0.2f, 0.2f, -0.5f}, {0.2f, 0.2f, -0.5f}};
  degenerate.normals.assign(6, glm::vec3(0, 0, 1));
  degenerate.uvs.assign(6, glm::vec2(0.0f));
  degenerate.indices = {0, 1, 2, 3, 4, 5};  // a collinear triangle and a point triangle
  degenerate.material = 0;
  s.meshes.push_back({"degenerate", {degenerate}});
  scene::Instance inst;
  inst.lod_meshes = {uint32_t(s.meshes.size() - 1)};
  s.instances.push_back(inst);
  render::RenderSettings rs;
  rs.width = 16;
  rs.height = 16;
  rs.spp = 16;
  render::Renderer r(gpu_context(), s, rs);
  expect_finite(r.render(s.frame_state(0), 0), "degenerate triangles");
}

TEST_F(Extreme, ExtremeImageShapes) {
  scene::Scene s = scene::builtin_scene("cornell");
  for (auto [w, h] : {std::pair{1u, 1u}, std::pair{2048u, 1u}, std::pair{1u, 1024u}, std::pair{3u, 577u}}) {
    render::RenderSettings rs;
    rs.width = w;
    rs.height = h;
    rs.spp = 2;
    render::Renderer r(gpu_context(), s, rs);
    auto result = r.render(s.frame_state(0), 0);
    expect_finite(result, std::to_string(w) + "x" + std::to_string(h));
    EXPECT_EQ(result.stats.paths, uint64_t(w) * h * 2);
  }
}

TEST_F(Extreme, LodSwitchEveryFrameAndTeleportingCamera) {
  scene::Scene s = scene::builtin_scene("chess");
  render::RenderSettings rs;
  rs.width = 24;
  rs.height = 16;
  rs.spp = 2;
  render::Renderer r(gpu_context(), s, rs);
  for (uint32_t f = 0; f < 12; ++f) {
    scene::FrameState frame = s.frame_state(f);
    for (size_t i = 0; i < frame.lods.size(); ++i)
      frame.lods[i] = (f + uint32_t(i)) % uint32_t(s.instances[i].lod_meshes.size());
    // Every other frame the camera jumps 1 km away and back, looking the other way.
    if (f % 2) {
      frame.camera.position += glm::vec3(1000.0f, 50.0f, -700.0f);
      frame.camera.orientation = glm::angleAxis(3.0f, glm::vec3(0, 1, 0)) * frame.camera.orientation;
    }
    auto result = r.render(frame, f);
    expect_finite(result, "frame " + std::to_string(f));
  }
}

TEST_F(Extreme, StiffSceneIsFiniteOverItsAnimation) {
  scene::Scene s = scene::builtin_scene("stiff");
  render::RenderSettings rs;
  rs.width = 32;
  rs.height = 24;
  rs.spp = 8;
  render::Renderer r(gpu_context(), s, rs);
  for (uint32_t f = 0; f < 120; f += 17) expect_finite(r.render(s.frame_state(f), f), "stiff frame " + std::to_string(f));
}

}  // namespace
}  // namespace strata::test
