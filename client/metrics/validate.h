#pragma once
// Input checks and masked pooling shared by every metric (internal to strata_metrics).
#include <cstdint>
#include <span>

#include "metrics/metrics.h"

namespace strata::metrics::detail {

// Throws MetricError when either image is empty, its rgba vector does not hold 4*width*height
// floats, or the two sizes differ; every message names the field and expected vs actual size.
void check_images(const image::Image& test, const image::Image& reference);

// Throws MetricError when a non-empty mask does not hold width*height bytes.
void check_mask(Mask mask, uint32_t width, uint32_t height);

// Throws MetricError naming `which` ("test" or "reference"), the pixel (x,y) and the channel of the
// first non-finite R, G or B value (alpha is ignored by every metric).
void check_finite(const image::Image& img, const char* which);

// All of the above, for both images.
void check_inputs(const image::Image& test, const image::Image& reference, Mask mask);

// Mean of `values` (one per pixel) over the pixels the mask selects; an empty mask selects every
// pixel, an all-zero mask gives mean 0 over 0 pixels.
struct Pooled {
  double mean = 0.0;
  uint64_t pixels = 0;
};
Pooled masked_mean(std::span<const float> values, Mask mask);

}  // namespace strata::metrics::detail
