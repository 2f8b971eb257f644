// KHR_lights_punctual on the device (include/scene_lights.glsl, docs/ARCHITECTURE.md "Light sampling"):
// the units of scene/scene.h against closed forms, and the unbiasedness of pt's and every ReSTIR
// method's estimates with point, spot and directional lights (a moving point light included) with
// the harness of tests/support/unbiasedness.h against converged pt references.
#include <cmath>
#include <cstdio>
#include <functional>
#include <string>
#include <vector>

#include <glm/gtc/matrix_transform.hpp>
#include <glm/gtc/quaternion.hpp>

#include "gpu/gpu_context.h"
#include "render/renderer.h"
#include "restir/sequence_runs.h"
#include "scene/scene_io.h"
#include "support/test_scenes.h"
#include "support/unbiasedness.h"

namespace strata::test {
namespace {

constexpr float kPi = 3.14159265358979f;

// A light at `position` shining down -Z (its node's transform), or along `direction`.
scene::Light make_light(scene::LightType type, float intensity, glm::vec3 position, glm::vec3 direction = {0, 0, -1}) {
  scene::Light l;
  l.name = "light";
  l.type = type;
  l.intensity = intensity;
  const glm::vec3 z = -glm::normalize(direction);  // the light's local +Z
  const glm::vec3 x = glm::normalize(glm::cross(std::abs(z.y) < 0.9f ? glm::vec3(0, 1, 0) : glm::vec3(1, 0, 0), z));
  l.transform = glm::mat4(glm::vec4(x, 0), glm::vec4(glm::cross(z, x), 0), glm::vec4(z, 0), glm::vec4(position, 1));
  return l;
}

// The white plane of tests/support/test_scenes.h lit by `light` alone.
scene::Scene lit_plane(const scene::Light& light) {
  scene::Scene s = white_plane("lit-plane");
  s.lights.push_back(light);
  s.validate();
  return s;
}

// The image's mean radiance (red channel: the lights are white).
double mean_radiance(const scene::Scene& s, const std::string& method, uint32_t frames) {
  render::RenderSettings rs;
  rs.width = 8;
  rs.height = 8;
  rs.method = method;
  rs.spp = method == "pt" ? 16 : 1;
  rs.max_depth = 2;
  render::Renderer renderer(gpu_context(), s, rs);
  double sum = 0.0;
  image::Image img;
  for (uint32_t f = 0; f < frames; ++f) img = renderer.render(s.frame_state(0), f).image;
  for (size_t i = 0; i < img.rgba.size(); i += 4) sum += img.rgba[i];
  return sum / double(img.rgba.size() / 4);
}

struct UnitCase {
  std::string name;
  scene::Light light;
  double expected;  // radiance at the plane's centre towards +Z
};

std::vector<UnitCase> unit_cases() {
  const float I = 5.0f, d = 2.0f;
  std::vector<UnitCase> v;
  // I / d^2 irradiance, Lambert albedo 1: L = I / (pi d^2).
  v.push_back({"point", make_light(scene::LightType::kPoint, I, {0, 0, d}), I / (kPi * d * d)});
  // A directional light's intensity is the irradiance facing it: L = E / pi.
  v.push_back({"directional", make_light(scene::LightType::kDirectional, I, {0, 0, 0}), I / kPi});
  // range 4 m at 2 m: KHR_lights_punctual's window clamp(1 - (d / range)^4, 0, 1) = 15/16.
  scene::Light ranged = make_light(scene::LightType::kPoint, I, {0, 0, d});
  ranged.range = 4.0f;
  v.push_back({"point_range", ranged, I / (kPi * d * d) * (15.0 / 16.0)});
  // A spot aimed 20 degrees off the plane's centre, cones 10 and 30 degrees: the extension's falloff
  // a = clamp((cos 20 - cos 30) / (cos 10 - cos 30), 0, 1)^2 there.
  const float tilt = glm::radians(20.0f);
  scene::Light spot = make_light(scene::LightType::kSpot, I, {0, 0, d}, {std::sin(tilt), 0.0f, -std::cos(tilt)});
  spot.inner_cone = glm::radians(10.0f);
  spot.outer_cone = glm::radians(30.0f);
  const double ramp = (std::cos(double(tilt)) - std::cos(glm::radians(30.0))) / (std::cos(glm::radians(10.0)) - std::cos(glm::radians(30.0)));
  v.push_back({"spot_falloff", spot, I / (kPi * d * d) * ramp * ramp});
  // Inside the inner cone: full intensity.
  scene::Light spot_full = spot;
  spot_full.inner_cone = glm::radians(25.0f);
  spot_full.outer_cone = glm::radians(40.0f);
  v.push_back({"spot_inner", spot_full, I / (kPi * d * d)});
  return v;
}

class PunctualUnits : public GpuTest, public ::testing::WithParamInterface<std::string> {};

// Every pixel sees a point within 6 mm of the centre, 2 m under the light: cos and 1/d^2 differ
// from the centre's by under 1e-5 (the spot ramp's square by under 1e-4 on average), and one light
// with pmf 1 leaves no variance but the pixel footprint's. Tolerance 2e-4 relative.
TEST_P(PunctualUnits, RadianceMatchesClosedForm) {
  const std::string method = GetParam();
  for (const UnitCase& c : unit_cases()) {
    const scene::Scene s = lit_plane(c.light);
    const double got = mean_radiance(s, method, method == "pt" ? 1 : 3);
    std::printf("%s %s: %.6f expected %.6f\n", method.c_str(), c.name.c_str(), got, c.expected);
    EXPECT_NEAR(got, c.expected, 2e-4 * c.expected) << method << " " << c.name;
  }
}

// The largest finite intensity (validate() refuses only non-finite ones): I / d^2 overflows float
// on the device, and the light sample is dropped there; no NaN or Inf reaches a pixel.
TEST_P(PunctualUnits, HugeIntensityNeverReachesAPixel) {
  const std::string method = GetParam();
  const scene::Scene s = lit_plane(make_light(scene::LightType::kPoint, 3e38f, {0, 0, 0.5f}));
  render::RenderSettings rs;
  rs.width = 8;
  rs.height = 8;
  rs.method = method;
  rs.max_depth = 2;
  render::Renderer renderer(gpu_context(), s, rs);
  for (uint32_t f = 0; f < 2; ++f)
    for (float v : renderer.render(s.frame_state(0), f).image.rgba) EXPECT_TRUE(std::isfinite(v)) << method;
}

INSTANTIATE_TEST_SUITE_P(Methods, PunctualUnits, ::testing::Values("pt", "restir-di", "restir-gather", "restir-splat"),
                         [](const ::testing::TestParamInfo<std::string>& p) { return method_test_name(p.param); });

// Unbiasedness: cornell (its ceiling emitter kept, so the light table mixes triangles and punctual
// lights) with punctual lights added.
struct Case {
  std::string name;
  std::function<void(scene::Scene&)> lights;
  SequenceRun run;
};

constexpr uint32_t kRuns = 64, kReferenceRuns = 24, kReferenceSpp = 64;

void add_point(scene::Scene& s) { s.lights.push_back(make_light(scene::LightType::kPoint, 1.5f, {0.4f, 1.5f, 0.2f})); }
void add_spot(scene::Scene& s) {
  // Down onto the floor between the boxes, the cone's edge across the floor and the boxes.
  scene::Light l = make_light(scene::LightType::kSpot, 4.0f, {-0.2f, 1.8f, 0.3f}, {0.2f, -1.0f, -0.1f});
  l.inner_cone = glm::radians(15.0f);
  l.outer_cone = glm::radians(35.0f);
  l.range = 3.0f;
  s.lights.push_back(l);
}
void add_directional(scene::Scene& s) {
  // Into the open front of the box, from above the camera.
  s.lights.push_back(make_light(scene::LightType::kDirectional, 1.2f, {0, 0, 0}, {-0.3f, -0.5f, -1.0f}));
}
void add_all(scene::Scene& s) {
  add_point(s);
  add_spot(s);
  add_directional(s);
}

// The point light moves 25 cm a frame along x and back: every temporal shift to it needs its
// previous frame's position.
scene::FrameState moving_point(const scene::Scene& s, uint32_t f) {
  scene::FrameState st = s.frame_state(0);
  const float x = (f % 2 == 0) ? -0.5f : 0.5f;
  st.lights[0] = glm::translate(glm::mat4(1.0f), {x, 0.0f, 0.0f}) * st.lights[0];
  return st;
}

class PunctualUnbiased : public GpuTest, public ::testing::WithParamInterface<Case> {};

TEST_P(PunctualUnbiased, MatchesPathTracedReference) {
  const Case& c = GetParam();
  scene::Scene s = scene::builtin_scene("cornell");
  c.lights(s);
  s.validate();
  expect_matches_pt(s, c.name, c.run, kRuns, kReferenceRuns, kReferenceSpp);
}

std::vector<Case> cases() {
  auto temporal_only = [](render::RestirOptions& o) { o.spatial = false; };
  std::vector<Case> v;
  v.push_back({"di_all_lights", add_all, {.method = "restir-di", .max_depth = 2}});
  v.push_back({"di_moving_point", add_point, {.method = "restir-di", .max_depth = 2, .state = moving_point, .options = temporal_only}});
  v.push_back({"gather_all_lights", add_all, {.method = "restir-gather"}});
  v.push_back({"gather_moving_point", add_point, {.method = "restir-gather", .state = moving_point, .options = temporal_only}});
  v.push_back({"splat_spot_directional", [](scene::Scene& s) {
                 add_spot(s);
                 add_directional(s);
               }, {.method = "restir-splat", .options = temporal_only}});
  v.push_back({"splat_moving_point", add_point, {.method = "restir-splat", .state = moving_point, .options = temporal_only}});
  // cornell-lamps (its spot, point light and sun, no emitter), nothing moving, over 12 frames: the
  // spatial passes' shifts must evaluate a path that ends at a punctual light as one. They did not
  // (compiled without the punctual lights), and with temporal and spatial reuse and the still
  // cap's confidence each frame's bias compounded into the next: +74% in the mean by frame 15.
  v.push_back({"gather_lamps_still", [](scene::Scene& s) { s = scene::builtin_scene("cornell-lamps"); },
               {.method = "restir-gather", .frames = 12}});
  return v;
}

INSTANTIATE_TEST_SUITE_P(Cases, PunctualUnbiased, ::testing::ValuesIn(cases()),
                         [](const ::testing::TestParamInfo<Case>& p) { return p.param.name; });

}  // namespace
}  // namespace strata::test
