// A small area light near a surface far from the camera, against its closed form for pt and every
// ReSTIR method's next-event estimation: the white plane of tests/support/test_scenes.h (3 m from
// the camera) under a one-sided emissive square 0.2 m above it, beside the camera's view. A visibility ray's origin is offset
// from the plane by 256 ulps of its render-space coordinates (sampling/ray_offset.h); aimed from the
// plane point instead of from that origin, every shadow ray ended past the light's surface and hit
// it, so that next-event estimation saw nothing there (aim_ray).
#include <cmath>
#include <cstdio>
#include <string>

#include "gpu/gpu_context.h"
#include "render/renderer.h"
#include "support/test_scenes.h"

namespace strata::test {
namespace {

constexpr double kPi = 3.14159265358979;

// The form factor from a differential area to a parallel rectangle X h x Y h whose corner lies h
// above it (Howell's catalogue, B-3): the share of a Lambertian receiver's irradiance per unit of
// the rectangle's radiance, over pi.
double corner_form_factor(double x, double y) {
  const double a = std::sqrt(1.0 + x * x), b = std::sqrt(1.0 + y * y);
  return (x / a * std::atan(y / a) + y / b * std::atan(x / b)) / (2.0 * kPi);
}

// The square: 0.1 m wide, its near edge 5 cm beside the point under the camera (x in [0.05, 0.15],
// y in [-0.05, 0.05]), 0.2 m above the plane, facing it.
constexpr float kHalf = 0.05f, kOffset = 0.1f, kHeight = 0.2f, kRadiance = 10.0f;

scene::Scene plane_under_light() {
  scene::Scene s = white_plane("plane-under-light");
  scene::Material light;
  light.name = "light";
  light.base_color = glm::vec3(0.0f);
  light.emission = glm::vec3(kRadiance);
  s.materials.push_back(light);
  scene::Mesh m = quad_mesh(kHalf, kHeight, 1);
  // Facing -Z, down to the plane: the quad's winding reversed.
  for (size_t t = 0; t < m.primitives[0].indices.size(); t += 3) std::swap(m.primitives[0].indices[t + 1], m.primitives[0].indices[t + 2]);
  for (glm::vec3& n : m.primitives[0].normals) n = -n;
  m.name = "light";
  s.meshes.push_back(m);
  scene::Instance inst;
  inst.name = "light";
  inst.lod_meshes = {uint32_t(s.meshes.size() - 1)};
  inst.transform[3] = glm::vec4(kOffset, 0.0f, 0.0f, 1.0f);
  s.instances.push_back(inst);
  s.validate();
  return s;
}

class AreaLightUnits : public GpuTest, public ::testing::WithParamInterface<std::string> {};

// Every pixel sees a point within 6 mm of the centre, where the irradiance changes linearly to
// first order (the mean over the symmetric pixels cancels it; the second order is under 1e-3). The
// radiance of a white Lambert plane there is L (the square's form factor), the difference of two
// rectangles with a corner above it: 2 L (F(0.15 / h, a / h) - F(0.05 / h, a / h)). One light
// sample's estimate varies by a factor of 2 over the square (h^2 / r^4), so pt takes 256 samples a
// pixel (8 x 8 pixels: standard error about 0.3%), and a ReSTIR method's mean is over 16 frames,
// whose reservoirs share samples across pixels and frames (means over seeds 3, 11 and 12 within
// 0.3% for pt and 2.1% for ReSTIR). Tolerance 4%. With every shadow ray blocked by the light the
// mean is the BSDF hits' MIS-weighted share alone: under 1% of it (0.0016 to 0.0023 here).
TEST_P(AreaLightUnits, SmallLightNearAFarSurfaceMatchesClosedForm) {
  const std::string method = GetParam();
  const scene::Scene s = plane_under_light();
  render::RenderSettings rs;
  rs.width = 8;
  rs.height = 8;
  rs.method = method;
  rs.spp = method == "pt" ? 256 : 1;
  rs.max_depth = 2;
  rs.seed = 3;
  render::Renderer renderer(gpu_context(), s, rs);
  const uint32_t frames = method == "pt" ? 1 : 16;
  double sum = 0.0;
  size_t n = 0;
  for (uint32_t f = 0; f < frames; ++f) {
    const image::Image img = renderer.render(s.frame_state(0), f).image;
    for (size_t i = 0; i < img.rgba.size(); i += 4, ++n) sum += img.rgba[i];
  }
  const double got = sum / double(n);
  const double near = kOffset - kHalf, far = kOffset + kHalf;
  const double expected = 2.0 * kRadiance * (corner_form_factor(far / kHeight, kHalf / kHeight) - corner_form_factor(near / kHeight, kHalf / kHeight));
  std::printf("%s: %.5f expected %.5f\n", method.c_str(), got, expected);
  EXPECT_NEAR(got, expected, 0.04 * expected) << method;
}

INSTANTIATE_TEST_SUITE_P(Methods, AreaLightUnits, ::testing::Values("pt", "restir-di", "restir-gather", "restir-splat"),
                         [](const ::testing::TestParamInfo<std::string>& p) { return method_test_name(p.param); });

}  // namespace
}  // namespace strata::test
