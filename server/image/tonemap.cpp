#include "image/tonemap.h"

#include <algorithm>
#include <cmath>

namespace strata::image {

float aces_narkowicz(float x) {
  // Beyond this the curve is above 1 (its limit is 2.51/2.43) and x*x would overflow for huge x,
  // turning the ratio into inf/inf; clamping first keeps every finite input well defined.
  constexpr float kSaturated = 1.0e4f;
  x = std::clamp(x, 0.0f, kSaturated);
  const float y = (x * (2.51f * x + 0.03f)) / (x * (2.43f * x + 0.59f) + 0.14f);
  return std::clamp(y, 0.0f, 1.0f);
}

float srgb_oetf(float linear) {
  const float c = std::clamp(linear, 0.0f, 1.0f);
  return c <= 0.0031308f ? 12.92f * c : 1.055f * std::pow(c, 1.0f / 2.4f) - 0.055f;
}

uint8_t tonemap_to_srgb8(float linear, float exposure_scale) {
  const float encoded = srgb_oetf(aces_narkowicz(linear * exposure_scale));
  return static_cast<uint8_t>(std::lround(encoded * 255.0f));
}

}  // namespace strata::image
