// White furnace: inside a closed box whose walls all emit Le and reflect with Lambert albedo a,
// the radiance is Le / (1 - a) everywhere (the Neumann series of the rendering equation). The path
// tracer's next-event estimation, light PDF and MIS weights all contribute, so an error in any of
// them moves the mean away from the analytic value.
#include <cmath>

#include "gpu/gpu_context.h"
#include "render/renderer.h"
#include "support/image_moments.h"
#include "support/test_scenes.h"

namespace strata::test {
namespace {

class Furnace : public GpuTest {};

TEST_F(Furnace, RadianceIsEmissionOverOneMinusAlbedo) {
  for (float albedo : {0.3f, 0.7f}) {
    scene::Scene s = furnace_box(albedo, 1.0f);
    render::RenderSettings rs;
    rs.width = 32;
    rs.height = 32;
    rs.spp = 64;
    rs.max_depth = 128;
    rs.seed = 7;
    render::Renderer r(gpu_context(), s, rs);
    auto result = r.render(s.frame_state(0), 0);
    double expected = 1.0 / (1.0 - albedo);
    for (int c = 0; c < 3; ++c) {
      ImageMoments m = channel_moments(result.image, c);
      // Pixels are independent Monte Carlo estimates, so the image mean is normal to good accuracy
      // with the measured standard error. 5 sigma keeps false failures below 1e-6 per check; the
      // 0.2% floor covers float accumulation and the truncation at max_depth (albedo^128 ~ 0).
      double tolerance = 5.0 * m.std_error + 2e-3 * expected;
      EXPECT_NEAR(m.mean, expected, tolerance) << "albedo " << albedo << " channel " << c << " se " << m.std_error;
      EXPECT_LT(m.std_error, 0.05 * expected) << "estimate too noisy to be a meaningful test";
    }
    EXPECT_EQ(result.stats.nonfinite_rejected, 0u);
    EXPECT_EQ(result.stats.paths, 32u * 32u * 64u);
  }
}

// Same furnace through a thin lens: every lens ray still starts inside the box, so the answer is
// unchanged while the lens sampling code runs.
TEST_F(Furnace, ThinLensDoesNotChangeTheFurnace) {
  scene::Scene s = furnace_box(0.5f, 1.0f);
  s.camera.aperture = 0.2f;
  s.camera.focus_distance = 0.8f;
  render::RenderSettings rs;
  rs.width = 24;
  rs.height = 24;
  rs.spp = 64;
  rs.max_depth = 128;
  render::Renderer r(gpu_context(), s, rs);
  auto result = r.render(s.frame_state(0), 0);
  ImageMoments m = channel_moments(result.image, 0);
  EXPECT_NEAR(m.mean, 2.0, 5.0 * m.std_error + 4e-3);
  bool thin_lens_ran = false;
  for (const auto& d : result.stats.passes)
    if (d.pass == "path_trace") thin_lens_ran = d.reason.find("thin lens") != std::string::npos;
  EXPECT_TRUE(thin_lens_ran);
}

// A Lambert plane under a constant environment L: every point sees the environment over its whole
// upper hemisphere, so its radiance is albedo * L. Exercises environment NEE and its MIS weights.
TEST_F(Furnace, PlaneUnderConstantEnvironment) {
  scene::Scene s;
  s.name = "env-plane";
  scene::Material m;
  m.base_color = glm::vec3(0.6f);
  m.specular = 0.0f;
  s.materials.push_back(m);
  s.meshes.push_back(quad_mesh(100.0f, 0.0f, 0));
  scene::Instance inst;
  inst.lod_meshes = {0};
  s.instances.push_back(inst);
  s.environment.radiance = glm::vec3(2.0f, 1.0f, 0.5f);
  s.camera.position = glm::vec3(0.0f, 0.0f, 1.0f);  // looks down -Z at the plane
  s.camera.yfov = 0.5f;
  render::RenderSettings rs;
  rs.width = 24;
  rs.height = 24;
  rs.spp = 64;
  render::Renderer r(gpu_context(), s, rs);
  auto result = r.render(s.frame_state(0), 0);
  const double expected[3] = {1.2, 0.6, 0.3};
  for (int c = 0; c < 3; ++c) {
    ImageMoments mo = channel_moments(result.image, c);
    EXPECT_NEAR(mo.mean, expected[c], 5.0 * mo.std_error + 2e-3 * expected[c]) << "channel " << c;
  }
}

}  // namespace
}  // namespace strata::test
