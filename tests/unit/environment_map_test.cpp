// Environment maps: decoding (Radiance .hdr), the direction <-> UV mapping, and importance sampling
// by luminance x solid angle: the pdf integrates to 1 over the sphere, samples follow it, and the
// estimator of the map's integral converges to the exact value.
#include <cmath>
#include <fstream>
#include <random>

#include <gtest/gtest.h>

#include "image/image.h"
#include "scene/environment_map.h"

namespace strata::scene {
namespace {

constexpr double kPi = 3.14159265358979323846;

EnvironmentMap random_map(uint32_t w, uint32_t h, float rotation) {
  EnvironmentMap m;
  m.width = w;
  m.height = h;
  m.rotation = rotation;
  std::mt19937 rng(7);
  std::uniform_real_distribution<float> r(0.0f, 1.0f);
  for (uint32_t k = 0; k < w * h; ++k) {
    const float s = r(rng) < 0.1f ? 50.0f : 1.0f;  // a few bright texels, like a sun
    m.radiance.push_back(glm::vec3(r(rng), r(rng), r(rng)) * s);
  }
  m.radiance[5] = glm::vec3(0.0f);  // a black texel is never sampled
  build_environment_tables(m);
  return m;
}

std::vector<uint8_t> file_bytes(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

TEST(EnvironmentMap, RadianceHdrDecodesTopRowFirst) {
  // tests/data/environment/sky_8x4.hdr: texel i (row-major) = (0.1 i, 1, 4), written by stb_image_write.
  const EnvironmentMap m = load_environment_map(std::string(STRATA_TEST_DATA_DIR) + "/environment/sky_8x4.hdr",
                                                {2.0f, 90.0f});
  ASSERT_EQ(m.width, 8u);
  ASSERT_EQ(m.height, 4u);
  for (uint32_t i : {1u, 9u, 31u}) {
    // RGBE shares one exponent: each channel is exact to 1/128 of the largest (4).
    EXPECT_NEAR(m.radiance[i].r, 0.1f * float(i), 0.04f) << i;
    EXPECT_NEAR(m.radiance[i].g, 1.0f, 0.04f);
    EXPECT_NEAR(m.radiance[i].b, 4.0f, 0.04f);
  }
  EXPECT_FLOAT_EQ(m.intensity, 2.0f);
  EXPECT_NEAR(m.rotation, float(kPi / 2), 1e-6f);
  EXPECT_GT(m.weight_sum, 0.0);
}

TEST(EnvironmentMap, FilesThatAreNotHdrImagesAndBadOptionsAreRefused) {
  const std::vector<uint8_t> rgb(3 * 4, 10);
  const std::vector<uint8_t> png = image::encode_png_rgb8(rgb, 2, 2);
  try {
    decode_environment_map(png, "sky.png");
    ADD_FAILURE() << "decoded";
  } catch (const SceneError& e) {
    EXPECT_STREQ(e.what(), "environment file 'sky.png' is not an HDR image (Radiance .hdr or OpenEXR): it is a PNG image");
  }
  const std::vector<uint8_t> hdr = file_bytes(std::string(STRATA_TEST_DATA_DIR) + "/environment/sky_8x4.hdr");
  EXPECT_THROW(decode_environment_map(hdr, "sky.hdr", {std::nanf(""), 0.0f}), SceneError);
  EXPECT_THROW(decode_environment_map(hdr, "sky.hdr", {1.0f, INFINITY}), SceneError);
  EXPECT_THROW(decode_environment_map(std::span(hdr).first(hdr.size() / 2), "sky.hdr"), SceneError);
  EnvironmentOptions small;
  small.max_dimension = 4;
  EXPECT_THROW(decode_environment_map(hdr, "sky.hdr", small), SceneError);
}

TEST(EnvironmentMap, DirectionsAndUvsRoundTripAndTheCentreLooksDownMinusZ) {
  const EnvironmentMap m = random_map(16, 8, 0.7f);
  for (float u : {0.1f, 0.5f, 0.9f}) {
    for (float v : {0.2f, 0.5f, 0.8f}) {
      const glm::vec2 back = environment_uv(m, environment_direction(m, {u, v}));
      EXPECT_NEAR(back.x, u, 1e-5f);
      EXPECT_NEAR(back.y, v, 1e-5f);
    }
  }
  EnvironmentMap still = random_map(16, 8, 0.0f);
  const glm::vec3 forward = environment_direction(still, {0.5f, 0.5f});
  EXPECT_NEAR(forward.z, -1.0f, 1e-6f);
  EXPECT_NEAR(environment_direction(still, {0.75f, 0.5f}).x, 1.0f, 1e-6f);
  EXPECT_NEAR(environment_direction(still, {0.5f, 0.0f}).y, 1.0f, 1e-6f);
}

TEST(EnvironmentMap, PdfIntegratesToOneOverTheSphere) {
  const EnvironmentMap m = random_map(16, 8, 0.3f);
  // Midpoint rule on a UV grid finer than the texels: dw = 2 pi^2 sin(theta) du dv.
  const int nu = 256, nv = 128;
  double integral = 0.0;
  for (int j = 0; j < nv; ++j) {
    for (int i = 0; i < nu; ++i) {
      const glm::vec2 uv((float(i) + 0.5f) / nu, (float(j) + 0.5f) / nv);
      const double sin_theta = std::sin(kPi * uv.y);
      integral += double(environment_pdf(m, environment_direction(m, uv))) * 2.0 * kPi * kPi * sin_theta / (nu * nv);
    }
  }
  EXPECT_NEAR(integral, 1.0, 2e-3);
}

TEST(EnvironmentMap, SamplesFollowThePdfAndEstimateTheIntegral) {
  const EnvironmentMap m = random_map(16, 8, 0.3f);
  std::mt19937 rng(11);
  std::uniform_real_distribution<float> r(0.0f, 1.0f);
  const int n = 200000;
  std::vector<int> hits(16 * 8, 0);
  double estimate = 0.0;
  for (int k = 0; k < n; ++k) {
    const EnvironmentSample s = sample_environment(m, {r(rng), r(rng)});
    ASSERT_GT(s.pdf, 0.0f);
    const glm::vec2 uv = environment_uv(m, s.direction);
    // The direction is stored in floats: within 1e-3 texel of a texel's edge it may come back in
    // the neighbouring texel, and within a few degrees of a pole float acos loses the polar angle.
    const float fu = uv.x * 16 - std::floor(uv.x * 16), fv = uv.y * 8 - std::floor(uv.y * 8);
    if (std::min({fu, 1 - fu, fv, 1 - fv}) > 1e-3f && std::sin(float(kPi) * uv.y) > 0.05f) {
      EXPECT_NEAR(s.pdf, environment_pdf(m, s.direction), 1e-3f * s.pdf);
    }
    const int i = std::min(15, int(uv.x * 16)), j = std::min(7, int(uv.y * 8));
    ++hits[size_t(j * 16 + i)];
    const glm::vec3 l = environment_radiance(m, s.direction);
    estimate += (0.2126 * l.r + 0.7152 * l.g + 0.0722 * l.b) / s.pdf / n;
  }
  EXPECT_EQ(hits[5], 0);  // the black texel
  // Texel frequencies match the tables within 5 standard deviations.
  for (uint32_t j = 0; j < 8; ++j) {
    for (uint32_t i = 0; i < 16; ++i) {
      const double p = (double(m.marginal_cdf[j + 1]) - m.marginal_cdf[j]) *
                       (double(m.conditional_cdf[j * 17 + i + 1]) - m.conditional_cdf[j * 17 + i]);
      EXPECT_NEAR(hits[j * 16 + i], n * p, 5.0 * std::sqrt(n * p) + 1.0) << i << ", " << j;
    }
  }
  // The exact integral of the luminance: each texel times its solid angle.
  double exact = 0.0;
  for (uint32_t j = 0; j < 8; ++j) {
    const double omega = 2.0 * kPi / 16 * (std::cos(kPi * j / 8) - std::cos(kPi * (j + 1) / 8));
    for (uint32_t i = 0; i < 16; ++i) {
      const glm::vec3 l = m.radiance[j * 16 + i];
      exact += (0.2126 * l.r + 0.7152 * l.g + 0.0722 * l.b) * omega;
    }
  }
  EXPECT_NEAR(estimate, exact, 0.01 * exact);
}

}  // namespace
}  // namespace strata::scene
