// Environment maps on the device (include/scene_lights.glsl, include/environment_data.h): a plane
// under a map against the irradiance integrated on the host, and the unbiasedness of every ReSTIR
// method with a map (its light choices mixed with the emitter table's, the camera moving) against
// converged pt references with the harness of tests/support/unbiasedness.h.
#include <cmath>
#include <cstdio>
#include <string>
#include <vector>

#include <glm/gtc/matrix_transform.hpp>

#include "gpu/gpu_context.h"
#include "render/renderer.h"
#include "restir/sequence_runs.h"
#include "scene/environment_map.h"
#include "scene/scene_io.h"
#include "support/image_moments.h"
#include "support/test_scenes.h"
#include "support/unbiasedness.h"

namespace strata::test {
namespace {

constexpr double kPi = 3.14159265358979323846;

// A 32 x 16 sky: a blue gradient above the horizon, a dark ground below, and a small sun (one
// texel of radiance 400, about 28 degrees up, towards +Z and -X) that carries most of the light.
// Rotated by `rotation_degrees` about +Y.
scene::EnvironmentMap test_sky(float rotation_degrees = 0.0f) {
  scene::EnvironmentMap m;
  m.name = "test-sky";
  m.width = 32;
  m.height = 16;
  m.radiance.resize(size_t(m.width) * m.height);
  for (uint32_t j = 0; j < m.height; ++j) {
    for (uint32_t i = 0; i < m.width; ++i) {
      const float v = (float(j) + 0.5f) / float(m.height);
      glm::vec3 c = v < 0.5f ? glm::vec3(0.25f, 0.4f, 0.9f) * (1.5f - v) : glm::vec3(0.08f, 0.06f, 0.05f);
      c *= 1.0f + 0.3f * std::sin(float(i) * 0.7f);  // varies along each row too
      m.radiance[size_t(j) * m.width + i] = c;
    }
  }
  m.radiance[size_t(5) * m.width + 3] = glm::vec3(400.0f, 380.0f, 350.0f);
  m.rotation = float(double(rotation_degrees) * kPi / 180.0);
  scene::build_environment_tables(m);
  return m;
}

// Irradiance on a surface of normal n under the map: each texel's radiance (constant over it, as
// the device reads it) times the integral of max(0, cos) over its solid angle, by 16 x 16
// sub-cells of solid angle 2 pi^2 sin(theta) du dv (scene/environment_map.h).
glm::dvec3 irradiance(const scene::EnvironmentMap& m, glm::vec3 n) {
  constexpr int kSub = 16;
  glm::dvec3 e(0.0);
  for (uint32_t j = 0; j < m.height; ++j) {
    for (uint32_t i = 0; i < m.width; ++i) {
      double weight = 0.0;
      for (int b = 0; b < kSub; ++b) {
        for (int a = 0; a < kSub; ++a) {
          const glm::vec2 uv((float(i) + (float(a) + 0.5f) / kSub) / float(m.width), (float(j) + (float(b) + 0.5f) / kSub) / float(m.height));
          const double cos_n = std::max(0.0f, glm::dot(scene::environment_direction(m, uv), n));
          const double d_omega = 2.0 * kPi * kPi * std::sin(kPi * double(uv.y)) / (double(m.width) * m.height * kSub * kSub);
          weight += cos_n * d_omega;
        }
      }
      e += glm::dvec3(m.radiance[size_t(j) * m.width + i] * m.intensity) * weight;
    }
  }
  return e;
}

// The white plane of tests/support/test_scenes.h (facing +Z) alone under the sky.
scene::Scene plane_under(const scene::EnvironmentMap& sky) {
  scene::Scene s = white_plane("sky-plane");
  s.environment.map = sky;
  s.validate();
  return s;
}

// The plane's radiance is E / pi. pt at 16 x 16 pixels and 256 samples each: the per-pixel
// estimates are independent, so the image mean's standard error is their spread over sqrt(pixels);
// 5 standard errors (a false failure about once in 1.7 million runs per channel) plus 1e-4 relative
// for the host integral's sub-cells. Run with the map turned, so that its rotation is checked too.
TEST_F(GpuTest, EnvironmentMapLightsAPlaneAsIntegrated) {
  for (float rotation : {0.0f, 75.0f}) {
    const scene::EnvironmentMap sky = test_sky(rotation);
    const scene::Scene s = plane_under(sky);
    const glm::dvec3 expected = irradiance(sky, glm::vec3(0, 0, 1)) / kPi;
    render::RenderSettings rs;
    rs.width = 16;
    rs.height = 16;
    rs.spp = 256;
    rs.max_depth = 2;
    render::Renderer renderer(gpu_context(), s, rs);
    const auto result = renderer.render(s.frame_state(0), 0);
    for (int c = 0; c < 3; ++c) {
      const ImageMoments mo = channel_moments(result.image, c);
      std::printf("rotation %.0f channel %d: %.5f expected %.5f (se %.5f)\n", rotation, c, mo.mean, expected[c], mo.std_error);
      EXPECT_NEAR(mo.mean, expected[c], 5.0 * mo.std_error + 1e-4 * expected[c]) << "rotation " << rotation << " channel " << c;
    }
    EXPECT_EQ(result.stats.nonfinite_rejected, 0u);
  }
}

// Unbiasedness: cornell (its ceiling emitter kept, so that the light sampler chooses between the
// emitter table and the map by power) under the sky, which enters through the box's open front.
struct Case {
  std::string name;
  SequenceRun run;
};

class EnvironmentUnbiased : public GpuTest, public ::testing::WithParamInterface<Case> {};

constexpr uint32_t kRuns = 64, kReferenceRuns = 24, kReferenceSpp = 64;

TEST_P(EnvironmentUnbiased, MatchesPathTracedReference) {
  const Case& c = GetParam();
  scene::Scene s = scene::builtin_scene("cornell");
  s.environment.map = test_sky();  // the sun in front of the box, shining in
  s.validate();
  expect_matches_pt(s, c.name, c.run, kRuns, kReferenceRuns, kReferenceSpp);
}

// The camera steps sideways and back each frame: temporal shifts of paths that end in the sky
// reconnect to it from other surfaces.
scene::FrameState moving_camera(const scene::Scene& s, uint32_t f) {
  scene::FrameState st = s.frame_state(0);
  st.camera.position.x += (f % 2 == 0) ? -0.04f : 0.04f;
  return st;
}

std::vector<Case> cases() {
  auto temporal_only = [](render::RestirOptions& o) { o.spatial = false; };
  std::vector<Case> v;
  v.push_back({"di", {.method = "restir-di", .max_depth = 2}});
  v.push_back({"gather_moving_camera", {.method = "restir-gather", .state = moving_camera}});
  v.push_back({"splat_temporal", {.method = "restir-splat", .state = moving_camera, .options = temporal_only}});
  return v;
}

INSTANTIATE_TEST_SUITE_P(Cases, EnvironmentUnbiased, ::testing::ValuesIn(cases()),
                         [](const ::testing::TestParamInfo<Case>& p) { return p.param.name; });

}  // namespace
}  // namespace strata::test
