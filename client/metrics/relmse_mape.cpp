// RelMSE (of RGB and of the luminance) and MAPE on linear RGB (alpha ignored), optionally restricted
// to a pixel mask.
#include <cmath>

#include "metrics/metrics.h"
#include "metrics/validate.h"

namespace strata::metrics {
namespace {

// Mean over the selected pixels and their three channels of term(t, r); 0 when the mask selects
// no pixel.
template <typename Term>
double mean_over_channels(const image::Image& test, const image::Image& reference, Mask mask, Term term) {
  detail::check_inputs(test, reference, mask);
  const size_t n = size_t(reference.width) * reference.height;
  double sum = 0.0;
  uint64_t pixels = 0;
  for (size_t i = 0; i < n; ++i) {
    if (!mask.empty() && mask[i] == 0) continue;
    const float* t = &test.rgba[4 * i];
    const float* r = &reference.rgba[4 * i];
    for (int c = 0; c < 3; ++c) sum += term(double(t[c]), double(r[c]));
    ++pixels;
  }
  return pixels > 0 ? sum / (3.0 * double(pixels)) : 0.0;
}

void check_eps(double eps) {
  if (!(eps > 0.0) || !std::isfinite(eps)) {
    throw MetricError("eps must be finite and > 0, got " + std::to_string(eps));
  }
}

}  // namespace

double relmse(const image::Image& test, const image::Image& reference, Mask mask, double eps) {
  check_eps(eps);
  return mean_over_channels(test, reference, mask, [eps](double t, double r) {
    const double d = t - r;
    return d * d / (r * r + eps);
  });
}

double relmse_luminance(const image::Image& test, const image::Image& reference, Mask mask, double eps) {
  check_eps(eps);
  detail::check_inputs(test, reference, mask);
  const size_t n = size_t(reference.width) * reference.height;
  auto luminance = [](const float* p) { return 0.2126 * double(p[0]) + 0.7152 * double(p[1]) + 0.0722 * double(p[2]); };
  double sum = 0.0;
  uint64_t pixels = 0;
  for (size_t i = 0; i < n; ++i) {
    if (!mask.empty() && mask[i] == 0) continue;
    const double yt = luminance(&test.rgba[4 * i]), yr = luminance(&reference.rgba[4 * i]);
    sum += (yt - yr) * (yt - yr) / (yr * yr + eps);
    ++pixels;
  }
  return pixels > 0 ? sum / double(pixels) : 0.0;
}

double mape(const image::Image& test, const image::Image& reference, Mask mask, double eps) {
  check_eps(eps);
  return mean_over_channels(test, reference, mask,
                            [eps](double t, double r) { return std::abs(t - r) / (std::abs(r) + eps); });
}

}  // namespace strata::metrics
