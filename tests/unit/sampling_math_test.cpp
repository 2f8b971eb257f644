// CPU tests of the sampling math that the passes run: the same headers, compiled as C++.
#include <gtest/gtest.h>

#include <cmath>
#include <numeric>
#include <vector>

#include "material/bsdf.h"
#include "render/emitters.h"
#include "sampling/mis.h"
#include "sampling/ray_offset.h"
#include "sampling/rng.h"
#include "sampling/warp.h"

namespace strata::gpu {
namespace {

TEST(SamplingMis, PowerHeuristicHandValues) {
  EXPECT_FLOAT_EQ(mis_power(1.0f, 1.0f), 0.5f);
  EXPECT_FLOAT_EQ(mis_power(2.0f, 1.0f), 0.8f);  // 4 / (4 + 1)
  EXPECT_FLOAT_EQ(mis_power(1.0f, 2.0f), 0.2f);
  EXPECT_FLOAT_EQ(mis_power(3.0f, 0.0f), 1.0f);
  EXPECT_FLOAT_EQ(mis_power(0.0f, 3.0f), 0.0f);
  EXPECT_FLOAT_EQ(mis_power(0.0f, 0.0f), 1.0f);  // no other strategy either: keep the sample
  float inf = std::numeric_limits<float>::infinity();
  EXPECT_FLOAT_EQ(mis_power(inf, 1.0f), 1.0f);
  EXPECT_FLOAT_EQ(mis_power(1.0f, inf), 0.0f);
  // Weights of the two strategies for one path sum to one.
  for (float a : {0.1f, 1.0f, 7.0f})
    for (float b : {0.2f, 3.0f}) EXPECT_NEAR(mis_power(a, b) + mis_power(b, a), 1.0f, 1e-6f);
}

TEST(SamplingWarp, CosineHemisphereMoments) {
  Rng rng = rng_init(1, 2, 3, 4);
  double sum_z = 0.0;
  const int n = 200000;
  for (int i = 0; i < n; ++i) {
    vec3 d = sample_cosine_hemisphere(rng_next_float2(rng));
    ASSERT_GE(d.z, 0.0f);
    ASSERT_NEAR(length(d), 1.0f, 1e-5f);
    sum_z += d.z;
  }
  // E[cos] under cos/pi is 2/3; the standard deviation of cos is sqrt(1/2 - 4/9) = 0.236, so the
  // standard error at n = 2e5 is 5.3e-4: 6e-3 is > 10 sigma yet catches a uniform sampler (1/2).
  EXPECT_NEAR(sum_z / n, 2.0 / 3.0, 6e-3);
}

TEST(SamplingWarp, TriangleBarycentricsAreUniform) {
  Rng rng = rng_init(9, 9, 9, 9);
  double s1 = 0.0, s2 = 0.0;
  const int n = 100000;
  for (int i = 0; i < n; ++i) {
    vec2 b = sample_triangle_barycentrics(rng_next_float2(rng));
    ASSERT_GE(b.x, 0.0f);
    ASSERT_GE(b.y, 0.0f);
    ASSERT_LE(b.x + b.y, 1.0f + 1e-6f);
    s1 += b.x;
    s2 += b.y;
  }
  EXPECT_NEAR(s1 / n, 1.0 / 3.0, 5e-3);  // sd 0.236, se 7.5e-4
  EXPECT_NEAR(s2 / n, 1.0 / 3.0, 5e-3);
}

TEST(SamplingWarp, SolidAngleConversionRefusesGrazing) {
  EXPECT_FLOAT_EQ(area_to_solid_angle_pdf(2.0f, 9.0f, 0.5f), 36.0f);
  EXPECT_EQ(area_to_solid_angle_pdf(2.0f, 9.0f, 0.0f), 0.0f);
  EXPECT_EQ(area_to_solid_angle_pdf(2.0f, 0.0f, 1.0f), 0.0f);
}

TEST(SamplingRng, UniformAndDecorrelated) {
  Rng a = rng_init(0, 0, 0, 1), b = rng_init(0, 0, 0, 2);
  double sum = 0.0;
  int equal = 0;
  for (int i = 0; i < 100000; ++i) {
    float x = rng_next_float(a), y = rng_next_float(b);
    ASSERT_GE(x, 0.0f);
    ASSERT_LT(x, 1.0f);
    sum += x;
    equal += x == y;
  }
  EXPECT_NEAR(sum / 100000.0, 0.5, 5e-3);  // se 9e-4
  EXPECT_LT(equal, 10);
}

TEST(SamplingRayOffset, MovesToTheNormalSideAtAnyMagnitude) {
  for (float scale : {0.0f, 1e-3f, 1.0f, 1e3f, 1e5f, 1e7f}) {
    vec3 p(scale, -scale, 0.5f * scale);
    vec3 n = normalize(vec3(0.3f, -0.5f, 0.8f));
    vec3 o = offset_ray_origin(p, n);
    EXPECT_GT(dot(o - p, n), 0.0f) << "scale " << scale;
    // The offset stays a few ulps: far below a millimetre at 1e5 units.
    EXPECT_LT(length(o - p), std::max(1e-3f, scale * 1e-4f)) << "scale " << scale;
  }
}

// Numerical integration of the BSDF over the hemisphere with uniform directions.
struct BsdfIntegrals {
  vec3 albedo{0.0f};   // integral of f cos
  double pdf_mass = 0;  // integral of the pdf
};

BsdfIntegrals integrate(const BsdfParams& p, vec3 wo, int n) {
  Rng rng = rng_init(5, 6, 7, 8);
  BsdfIntegrals r;
  for (int i = 0; i < n; ++i) {
    vec3 wi = sample_uniform_sphere(rng_next_float2(rng));
    float inv_pdf = 4.0f * PI;
    r.albedo += bsdf_eval_cos(p, wo, wi) * (inv_pdf / float(n));
    r.pdf_mass += double(bsdf_pdf(p, wo, wi)) * inv_pdf / n;
  }
  return r;
}

TEST(SamplingBsdf, LambertOnlyWhenNoSpecular) {
  BsdfParams p = make_bsdf(vec3(0.5f, 0.25f, 1.0f), 0.0f, 1.0f, 0.0f);
  vec3 wo = normalize(vec3(0.2f, 0.1f, 0.9f));
  vec3 wi = normalize(vec3(-0.4f, 0.3f, 0.6f));
  vec3 f = bsdf_eval_cos(p, wo, wi);
  EXPECT_NEAR(f.r, 0.5f / PI * wi.z, 1e-6f);
  EXPECT_NEAR(f.g, 0.25f / PI * wi.z, 1e-6f);
  EXPECT_NEAR(bsdf_pdf(p, wo, wi), wi.z / PI, 1e-6f);
  EXPECT_EQ(bsdf_eval_cos(p, wo, vec3(0, 0, -1)), vec3(0.0f));
  // At grazing angles too: KHR_materials_specular's factor scales F90 as well as F0, so Schlick's
  // (1 - wo.h)^5 term adds nothing (with F90 = 1 it would add a rough highlight of about 0.2 / pi here).
  vec3 grazing_o = normalize(vec3(0.99f, 0.0f, 0.1f));
  vec3 grazing_i = normalize(vec3(-0.97f, 0.1f, 0.2f));
  vec3 g = bsdf_eval_cos(p, grazing_o, grazing_i);
  EXPECT_NEAR(g.r, 0.5f / PI * grazing_i.z, 1e-6f);
  EXPECT_NEAR(g.b, 1.0f / PI * grazing_i.z, 1e-6f);
}

TEST(SamplingBsdf, PdfIntegratesToOneAndEnergyIsConserved) {
  for (float roughness : {0.3f, 0.6f, 1.0f}) {
    for (float metallic : {0.0f, 1.0f}) {
      BsdfParams p = make_bsdf(vec3(0.9f), metallic, roughness, 1.0f);
      for (float cos_o : {0.9f, 0.4f}) {
        vec3 wo(std::sqrt(1.0f - cos_o * cos_o), 0.0f, cos_o);
        BsdfIntegrals r = integrate(p, wo, 400000);
        // The density integrates to the probability that bsdf_sample succeeds (reflected microfacet
        // directions that fall below the horizon are refused). Both are estimated: the uniform-sphere
        // estimate of a smooth lobe has ~1% error at 4e5 samples for alpha >= 0.09.
        Rng rng = rng_init(21, 22, 23, 24);
        int succeeded = 0;
        const int trials = 200000;
        for (int i = 0; i < trials; ++i) {
          vec3 wi, w;
          float pdf;
          succeeded += bsdf_sample(p, wo, vec3(rng_next_float2(rng), rng_next_float(rng)), wi, w, pdf);
        }
        double success = double(succeeded) / trials;
        EXPECT_NEAR(r.pdf_mass, success, 0.03) << "roughness " << roughness << " metallic " << metallic << " cos " << cos_o;
        if (metallic == 0.0f) {
          EXPECT_GT(success, 0.9);
        }
        EXPECT_LE(r.albedo.r, 1.02f) << "roughness " << roughness << " metallic " << metallic;
      }
    }
  }
}

TEST(SamplingBsdf, SampledWeightsMatchEvalOverPdf) {
  BsdfParams p = make_bsdf(vec3(0.8f, 0.5f, 0.3f), 0.3f, 0.4f, 1.0f);
  vec3 wo = normalize(vec3(0.5f, -0.2f, 0.7f));
  Rng rng = rng_init(11, 12, 13, 14);
  vec3 mean(0.0f);
  int n = 200000, ok = 0;
  for (int i = 0; i < n; ++i) {
    vec3 u(rng_next_float2(rng), rng_next_float(rng));
    vec3 wi, w;
    float pdf;
    if (!bsdf_sample(p, wo, u, wi, w, pdf)) continue;
    ++ok;
    ASSERT_NEAR(pdf, bsdf_pdf(p, wo, wi), 1e-4f * pdf);
    vec3 expect = bsdf_eval_cos(p, wo, wi) / pdf;
    ASSERT_NEAR(w.r, expect.r, 1e-4f * (1.0f + expect.r));
    mean += w / float(n);
  }
  // Importance-sampled albedo agrees with the uniform-sphere integral of eval (independent estimator).
  BsdfIntegrals r = integrate(p, wo, 400000);
  EXPECT_NEAR(mean.r, r.albedo.r, 0.02f);
  EXPECT_NEAR(mean.b, r.albedo.b, 0.02f);
  EXPECT_GT(ok, n * 9 / 10);
}

TEST(SamplingAlias, ReproducesWeightsExactly) {
  std::vector<double> w = {1.0, 0.0, 5.0, 2.5, 0.001, 10.0, 3.0};
  auto table = render::build_alias_table(w);
  ASSERT_EQ(table.size(), w.size());
  double total = std::accumulate(w.begin(), w.end(), 0.0);
  std::vector<double> p(w.size(), 0.0);
  for (size_t c = 0; c < table.size(); ++c) {
    p[c] += table[c].threshold / double(w.size());
    p[table[c].alias] += (1.0 - table[c].threshold) / double(w.size());
  }
  for (size_t i = 0; i < w.size(); ++i) EXPECT_NEAR(p[i], w[i] / total, 1e-6) << i;
}

}  // namespace
}  // namespace strata::gpu
