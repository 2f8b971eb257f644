#include "support/image_moments.h"

#include <algorithm>
#include <cmath>

namespace strata::test {

ImageMoments channel_moments(const image::Image& img, int channel) {
  const size_t n = size_t(img.width) * img.height;
  double sum = 0.0, sum2 = 0.0;
  for (size_t i = 0; i < n; ++i) {
    const double v = img.rgba[4 * i + size_t(channel)];
    sum += v;
    sum2 += v * v;
  }
  const double mean = sum / double(n);
  const double var = std::max(0.0, sum2 / double(n) - mean * mean);
  return {mean, std::sqrt(var / double(n))};
}

}  // namespace strata::test
