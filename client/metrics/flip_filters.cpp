// The filters of FLIP (FLIP20 colour pipeline: CSF spatial filtering; FLIP20 feature pipeline: edge
// and point detectors) and clamp-to-edge separable filtering on float planes.
#include <algorithm>
#include <cmath>
#include <numbers>
#include <thread>

#include "metrics/flip_colour.h"
#include "metrics/flip_internal.h"

namespace strata::metrics::detail {

int csf_radius(double pixels_per_degree) {
  const double b_max = std::max({kCsfAchromatic.b1, kCsfAchromatic.b2, kCsfRedGreen.b1, kCsfRedGreen.b2,
                                 kCsfBlueYellow.b1, kCsfBlueYellow.b2});
  const double pi2 = std::numbers::pi * std::numbers::pi;
  return int(std::ceil(3.0 * std::sqrt(b_max / (2.0 * pi2)) * pixels_per_degree));
}

CsfKernel csf_kernel(const CsfConstants& c, double pixels_per_degree) {
  CsfKernel k;
  k.radius = csf_radius(pixels_per_degree);
  const double pi = std::numbers::pi;
  const double a[2] = {c.a1, c.a2}, b[2] = {c.b1, c.b2};
  double mass[2] = {0.0, 0.0};  // each term's sum over the 2D grid
  std::vector<double> g[2];
  for (int i = 0; i < 2; ++i) {
    if (a[i] == 0.0) continue;  // the achromatic and red-green CSFs are single Gaussians
    g[i].resize(size_t(2 * k.radius + 1));
    double sum = 0.0;
    for (int t = -k.radius; t <= k.radius; ++t) {
      const double r = double(t) / pixels_per_degree;  // degrees
      g[i][size_t(t + k.radius)] = std::exp(-pi * pi * r * r / b[i]);
      sum += g[i][size_t(t + k.radius)];
    }
    // a sqrt(pi/b) exp(-pi^2 (x^2 + y^2) / b) = a sqrt(pi/b) G(x) G(y): its grid sum is a sqrt(pi/b) S^2.
    mass[i] = a[i] * std::sqrt(pi / b[i]) * sum * sum;
    k.g[i].resize(g[i].size());
    for (size_t j = 0; j < g[i].size(); ++j) k.g[i][j] = float(g[i][j] / sum);
  }
  const double total = mass[0] + mass[1];
  k.w[0] = mass[0] / total;
  k.w[1] = mass[1] / total;
  return k;
}

FeatureKernels feature_kernels(double pixels_per_degree) {
  FeatureKernels k;
  k.sigma = 0.5 * kFeatureWidthDeg * pixels_per_degree;
  k.radius = int(std::ceil(3.0 * k.sigma));
  const size_t n = size_t(2 * k.radius + 1);
  std::vector<double> g(n), d1(n), d2(n);
  double g_sum = 0.0, d1_pos = 0.0, d1_neg = 0.0, d2_pos = 0.0, d2_neg = 0.0;
  const double s2 = k.sigma * k.sigma;
  for (int t = -k.radius; t <= k.radius; ++t) {
    const size_t j = size_t(t + k.radius);
    const double x = double(t);
    g[j] = std::exp(-x * x / (2.0 * s2));
    d1[j] = -x * g[j];                   // d/dx of the Gaussian (up to 1/sigma^2)
    d2[j] = (x * x / s2 - 1.0) * g[j];   // d^2/dx^2 of the Gaussian (up to 1/sigma^2)
    g_sum += g[j];
    (d1[j] > 0.0 ? d1_pos : d1_neg) += std::abs(d1[j]);
    (d2[j] > 0.0 ? d2_pos : d2_neg) += std::abs(d2[j]);
  }
  k.g.resize(n);
  k.d1.resize(n);
  k.d2.resize(n);
  for (size_t j = 0; j < n; ++j) {
    k.g[j] = float(g[j] / g_sum);
    k.d1[j] = float(d1[j] / (d1[j] > 0.0 ? d1_pos : d1_neg));
    k.d2[j] = float(d2[j] / (d2[j] > 0.0 ? d2_pos : d2_neg));
  }
  return k;
}

void parallel_rows(uint32_t rows, const std::function<void(uint32_t)>& body) {
  const uint32_t hw = std::max(1u, std::thread::hardware_concurrency());
  const uint32_t threads = std::min(hw, std::max(1u, rows / 16));
  if (threads <= 1) {
    for (uint32_t y = 0; y < rows; ++y) body(y);
    return;
  }
  std::vector<std::jthread> pool;
  pool.reserve(threads);
  for (uint32_t t = 0; t < threads; ++t) {
    const uint32_t begin = uint32_t(uint64_t(rows) * t / threads);
    const uint32_t end = uint32_t(uint64_t(rows) * (t + 1) / threads);
    pool.emplace_back([begin, end, &body] {
      for (uint32_t y = begin; y < end; ++y) body(y);
    });
  }
}

Plane filter_separable(const Plane& in, const std::vector<float>& kx, const std::vector<float>& ky) {
  const uint32_t w = in.width, h = in.height;
  const int rx = int(kx.size() / 2), ry = int(ky.size() / 2);
  Plane tmp(w, h), out(w, h);
  // Horizontal pass: pad each row by replicating its end pixels, then a plain dot product.
  parallel_rows(h, [&](uint32_t y) {
    std::vector<float> row(size_t(w) + 2 * size_t(rx));
    const float* src = &in.v[size_t(y) * w];
    for (size_t i = 0; i < row.size(); ++i) {
      const int x = std::clamp(int(i) - rx, 0, int(w) - 1);
      row[i] = src[x];
    }
    float* dst = &tmp.v[size_t(y) * w];
    for (size_t i = 0; i < kx.size(); ++i) {  // tap-major, so that the inner loop vectorizes
      const float k = kx[i];
      const float* src_i = &row[i];
      for (uint32_t x = 0; x < w; ++x) dst[x] += k * src_i[x];
    }
  });
  // Vertical pass: accumulate whole rows (the source row index is clamped to the image).
  parallel_rows(h, [&](uint32_t y) {
    float* dst = &out.v[size_t(y) * w];
    for (size_t i = 0; i < ky.size(); ++i) {
      const int sy = std::clamp(int(y) + int(i) - ry, 0, int(h) - 1);
      const float* src = &tmp.v[size_t(sy) * w];
      const float k = ky[i];
      for (uint32_t x = 0; x < w; ++x) dst[x] += k * src[x];
    }
  });
  return out;
}

Plane filter_csf(const Plane& in, const CsfKernel& k) {
  Plane out = filter_separable(in, k.g[0], k.g[0]);
  if (k.w[1] == 0.0) return out;  // w[0] is then exactly 1
  const Plane second = filter_separable(in, k.g[1], k.g[1]);
  const float w0 = float(k.w[0]), w1 = float(k.w[1]);
  for (size_t i = 0; i < out.v.size(); ++i) out.v[i] = w0 * out.v[i] + w1 * second.v[i];
  return out;
}

}  // namespace strata::metrics::detail
