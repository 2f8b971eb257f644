// HDR-FLIP (Andersson, Nilsson, Shirley, Akenine-Moller 2021, "Visualizing Errors in Rendered High
// Dynamic Range Images", Eurographics short paper; cited as HDRFLIP21 with the section title): both
// images are exposure-compensated and tone-mapped with ACES at a range of exposures computed from
// the reference, LDR-FLIP is evaluated at each, and the per-pixel maximum is the error.
#include <algorithm>
#include <cmath>
#include <string>

#include "metrics/flip_internal.h"
#include "metrics/metrics.h"
#include "metrics/validate.h"

namespace strata::metrics {
namespace {
std::string stops(double v) { return std::to_string(v) + " stops"; }
}  // namespace

namespace detail {
namespace {

// HDRFLIP21, exposure range: the tone-mapped value that the brightest pixel (start exposure) and
// the median pixel (stop exposure) are mapped to.
constexpr double kToneTarget = 0.85;
// The ACES pre-exposure of Narkowicz's fit, which HDR-FLIP keeps (its x is 0.6 * exposed radiance).
constexpr double kAcesPreScale = 0.6;

double luminance(const float* rgb) {
  return 0.2126 * std::max(0.0, double(rgb[0])) + 0.7152 * std::max(0.0, double(rgb[1])) +
         0.0722 * std::max(0.0, double(rgb[2]));
}

}  // namespace

// Narkowicz's ACES fit f(y) = y (2.51 y + 0.03) / (y (2.43 y + 0.59) + 0.14) at y = 0.6 x. For y > 1
// numerator and denominator are divided by y^2 so that no huge input overflows (f -> 2.51 / 2.43,
// clamped to 1).
double aces_tonemap(double x) {
  const double y = kAcesPreScale * std::max(0.0, x);
  double f;
  if (y <= 1.0) {
    f = y * (2.51 * y + 0.03) / (y * (2.43 * y + 0.59) + 0.14);
  } else {
    const double u = 1.0 / y;
    f = (2.51 + 0.03 * u) / (2.43 + 0.59 * u + 0.14 * u * u);
  }
  return std::clamp(f, 0.0, 1.0);
}

// f(y) = t  <=>  (2.51 - 2.43 t) y^2 + (0.03 - 0.59 t) y - 0.14 t = 0; for t in (0, 1) the leading
// coefficient is positive and the constant negative, so there is exactly one positive root.
double aces_input_for(double t) {
  const double a = 2.51 - 2.43 * t, b = 0.03 - 0.59 * t, c = -0.14 * t;
  const double y = (-b + std::sqrt(b * b - 4.0 * a * c)) / (2.0 * a);
  return y / kAcesPreScale;
}

// HDRFLIP21, exposure range: start = log2(x85 / Y_max), stop = log2(x85 / Y_median), plus the
// finite-range rules documented in metrics.h for black and mostly black references.
ExposureRange automatic_exposure_range(const image::Image& reference) {
  const size_t n = size_t(reference.width) * reference.height;
  std::vector<double> lum(n);
  for (size_t i = 0; i < n; ++i) lum[i] = luminance(&reference.rgba[4 * i]);
  const double y_max = *std::max_element(lum.begin(), lum.end());
  if (!(y_max > kHdrFlipBlackLuminance)) return {0.0, 0.0};  // all black: no scale to expose for

  auto upper_median = [](std::vector<double>& v) {
    const auto mid = v.begin() + std::ptrdiff_t(v.size() / 2);
    std::nth_element(v.begin(), mid, v.end());
    return *mid;
  };
  double y_median = upper_median(lum);
  if (!(y_median > kHdrFlipBlackLuminance)) {
    std::vector<double> lit;
    for (double y : lum) {
      if (y > kHdrFlipBlackLuminance) lit.push_back(y);
    }
    y_median = upper_median(lit);  // not empty: y_max is lit
  }
  const double x85 = aces_input_for(kToneTarget);
  ExposureRange r;
  r.start = std::log2(x85 / y_max);
  r.stop = std::min(std::log2(x85 / y_median), r.start + kHdrFlipMaxAutoRange);
  return r;
}

}  // namespace detail

HdrFlipResult hdr_flip(const image::Image& test, const image::Image& reference, Mask mask,
                       const HdrFlipOptions& options) {
  detail::check_ppd(options.pixels_per_degree);
  detail::check_inputs(test, reference, mask);
  for (const auto& [value, name] : {std::pair{options.start_exposure, "start_exposure"},
                                    std::pair{options.stop_exposure, "stop_exposure"}}) {
    if (std::isinf(value)) throw MetricError(std::string(name) + " must be finite or NaN (automatic), got inf");
  }

  HdrFlipResult result;
  const bool automatic = std::isnan(options.start_exposure) || std::isnan(options.stop_exposure);
  const detail::ExposureRange range = automatic ? detail::automatic_exposure_range(reference) : detail::ExposureRange{};
  result.start_exposure = std::isnan(options.start_exposure) ? range.start : options.start_exposure;
  result.stop_exposure = std::isnan(options.stop_exposure) ? range.stop : options.stop_exposure;
  if (result.start_exposure > result.stop_exposure) {
    throw MetricError("start_exposure " + stops(result.start_exposure) + " is above stop_exposure " +
                      stops(result.stop_exposure) + (automatic ? " (one of them automatic)" : ""));
  }
  const double span = result.stop_exposure - result.start_exposure;
  if (span > kHdrFlipMaxRange) {
    throw MetricError("exposure range " + stops(span) + " exceeds the limit of " +
                      stops(kHdrFlipMaxRange));
  }
  // HDRFLIP21, exposure range: N = max(2, ceil(stop - start)) exposures evenly spaced in stops.
  result.exposures = uint32_t(std::max(2.0, std::ceil(span)));
  const double step = span / double(result.exposures - 1);

  const uint32_t w = reference.width, h = reference.height;
  // Exposure compensation 2^e, ACES, clamp to [0, 1]: the result is treated as linear RGB.
  auto tone_map = [w, h](const image::Image& img, double exposure) {
    const double scale = std::exp2(exposure);
    detail::LinearRgb out{detail::Plane(w, h), detail::Plane(w, h), detail::Plane(w, h)};
    detail::Plane* planes[3] = {&out.r, &out.g, &out.b};
    detail::parallel_rows(h, [&](uint32_t y) {
      for (size_t i = size_t(y) * w; i < size_t(y + 1) * w; ++i) {
        for (int c = 0; c < 3; ++c) planes[c]->v[i] = float(detail::aces_tonemap(scale * img.rgba[4 * i + c]));
      }
    });
    return out;
  };

  // HDRFLIP21: the HDR-FLIP error of a pixel is its largest LDR-FLIP error over the exposures.
  result.error_map.assign(size_t(w) * h, 0.0f);
  for (uint32_t k = 0; k < result.exposures; ++k) {
    if (k > 0 && step == 0.0) break;  // every exposure is the same one
    const double exposure = result.start_exposure + double(k) * step;
    const std::vector<float> e =
        detail::ldr_flip_linear(tone_map(test, exposure), tone_map(reference, exposure), options.pixels_per_degree);
    for (size_t i = 0; i < e.size(); ++i) result.error_map[i] = std::max(result.error_map[i], e[i]);
  }
  const detail::Pooled pooled = detail::masked_mean(result.error_map, mask);
  result.mean = pooled.mean;
  result.pixels = pooled.pixels;
  return result;
}

}  // namespace strata::metrics
