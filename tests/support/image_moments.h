#pragma once
// The mean of one channel over an image's pixels and its standard error, for tests whose pixels
// are independent estimates of the same value.
#include "image/image.h"

namespace strata::test {

struct ImageMoments {
  double mean = 0.0;
  double std_error = 0.0;  // of the mean over pixels (pixels are independent estimates)
};

ImageMoments channel_moments(const image::Image& img, int channel);

}  // namespace strata::test
