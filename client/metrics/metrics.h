#pragma once
// Image error metrics against a reference, for `strata eval`: RelMSE, MAPE and HDR-FLIP
// (Andersson et al. 2020, "FLIP: A Difference Evaluator for Alternating Images"; Andersson et al.
// 2021, "Visualizing Errors in Rendered High Dynamic Range Images"). Every metric can be restricted
// to a pixel mask (e.g. the disoccluded pixels of a frame).
#include <cstdint>
#include <limits>
#include <span>
#include <stdexcept>
#include <vector>

#include "image/image.h"

namespace strata::metrics {

struct MetricError : std::invalid_argument {
  using std::invalid_argument::invalid_argument;
};

// A mask has width*height bytes; non-zero = the pixel counts. An empty span means every pixel.
// A mask that selects no pixel gives a mean of 0 (FlipResult::pixels = 0), never NaN.
using Mask = std::span<const uint8_t>;

// Every metric throws MetricError when an image is empty, its rgba does not hold 4*width*height
// floats, the sizes differ, the mask is not empty and not width*height bytes long, or an R, G or B
// value is not finite (the message names "test" or "reference" and the pixel (x,y)).

// Relative MSE on RGB, per channel: mean over pixels and channels of (t - r)^2 / (r^2 + eps).
// eps must be finite and > 0 (MetricError otherwise).
double relmse(const image::Image& test, const image::Image& reference, Mask mask = {}, double eps = 1e-2);
// Relative MSE of the luminance Y = 0.2126 R + 0.7152 G + 0.0722 B: mean over pixels of
// (Y_t - Y_r)^2 / (Y_r^2 + eps). Beside relmse it separates colour noise (a pixel of the right
// brightness in the wrong hue: a luminance-target resampler holding one path of one light's colour)
// from brightness noise. eps as for relmse.
double relmse_luminance(const image::Image& test, const image::Image& reference, Mask mask = {}, double eps = 1e-2);
// Mean absolute percentage error on RGB: mean of |t - r| / (|r| + eps); eps as for relmse.
double mape(const image::Image& test, const image::Image& reference, Mask mask = {}, double eps = 1e-2);

// LDR-FLIP on display-referred sRGB images with values in [0, 1] (RGB; alpha ignored; values
// outside [0, 1] are clamped).
struct FlipOptions {
  double pixels_per_degree = 67.0;  // FLIP paper default: 0.7 m from a 0.7 m wide 3840 px monitor
};
struct FlipResult {
  double mean = 0.0;              // mean FLIP error over the (masked) pixels, in [0, 1]
  std::vector<float> error_map;   // width*height per-pixel errors of the whole image (mask ignored)
  uint64_t pixels = 0;            // pixels the mean is taken over
};
FlipResult ldr_flip(const image::Image& test, const image::Image& reference, Mask mask = {},
                    const FlipOptions& options = {});

// HDR-FLIP on linear HDR images: tone-maps both with ACES at exposures from start to stop
// (computed from the reference, Andersson 2021 Sec. 4) and takes the per-pixel maximum LDR-FLIP.
struct HdrFlipOptions : FlipOptions {
  // Explicit exposure range in stops; NaN = automatic from the reference. The automatic stop
  // exposure is clamped so that a mostly black reference still gives a finite range.
  double start_exposure = std::numeric_limits<double>::quiet_NaN();
  double stop_exposure = std::numeric_limits<double>::quiet_NaN();
};
// The automatic range (Andersson 2021): with x85 the ACES input that maps to 0.85 and Y the
// reference luminance (0.2126 R + 0.7152 G + 0.0722 B, negatives as 0) over every pixel (the mask
// does not change the range), start = log2(x85 / max Y) and stop = log2(x85 / median Y) (the upper
// median); N = max(2, ceil(stop - start)) exposures. The finite-range rules:
//  - luminances <= kHdrFlipBlackLuminance count as black; an all-black reference has no scale and
//    gives start = stop = 0 (two identical exposures);
//  - when the median is black (more than half the pixels), the median of the non-black pixels is
//    used instead;
//  - the automatic stop is at most start + kHdrFlipMaxAutoRange stops.
// An explicit range must be finite, with start <= stop and stop - start <= kHdrFlipMaxRange.
// Negative values tone-map as 0; any finite value (up to FLT_MAX) is fine.
inline constexpr double kHdrFlipBlackLuminance = 1e-9;
inline constexpr double kHdrFlipMaxAutoRange = 20.0;
inline constexpr double kHdrFlipMaxRange = 64.0;
struct HdrFlipResult : FlipResult {
  double start_exposure = 0.0, stop_exposure = 0.0;
  uint32_t exposures = 0;
};
HdrFlipResult hdr_flip(const image::Image& test, const image::Image& reference, Mask mask = {},
                       const HdrFlipOptions& options = {});

}  // namespace strata::metrics
