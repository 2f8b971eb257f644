// RelMSE (of RGB and of the luminance) and MAPE on linear RGB (alpha ignored), optionally restricted
// to a pixel mask.
#include <cmath>

#include "metrics/metrics.h"
#include "metrics/validate.h"

namespace strata::metrics {
namespace {

// Mean over the selected pixels of term(t, r), t and r a pixel's RGB; 0 when the mask selects no pixel.
template <typename Term>
double mean_over_pixels(const image::Image& test, const image::Image& reference, Mask mask, Term term) {
  detail::check_inputs(test, reference, mask);
  const size_t n = size_t(reference.width) * reference.height;
  double sum = 0.0;
  uint64_t pixels = 0;
  for (size_t i = 0; i < n; ++i) {
    if (!mask.empty() && mask[i] == 0) continue;
    sum += term(&test.rgba[4 * i], &reference.rgba[4 * i]);
    ++pixels;
  }
  return pixels > 0 ? sum / double(pixels) : 0.0;
}

// The same over the pixels' three channels: the mean of term(t_c, r_c).
template <typename Term>
double mean_over_channels(const image::Image& test, const image::Image& reference, Mask mask, Term term) {
  return mean_over_pixels(test, reference, mask, [&term](const float* t, const float* r) {
    double sum = 0.0;
    for (int c = 0; c < 3; ++c) sum += term(double(t[c]), double(r[c]));
    return sum / 3.0;
  });
}

double luminance(const float* rgb) { return 0.2126 * double(rgb[0]) + 0.7152 * double(rgb[1]) + 0.0722 * double(rgb[2]); }

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
  return mean_over_pixels(test, reference, mask, [eps](const float* t, const float* r) {
    const double d = luminance(t) - luminance(r);
    return d * d / (luminance(r) * luminance(r) + eps);
  });
}

double mape(const image::Image& test, const image::Image& reference, Mask mask, double eps) {
  check_eps(eps);
  return mean_over_channels(test, reference, mask,
                            [eps](double t, double r) { return std::abs(t - r) / (std::abs(r) + eps); });
}

}  // namespace strata::metrics
