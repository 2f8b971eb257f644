#pragma once
// The preview tonemap of encode_png_preview, exposed so that tests and tools can reproduce it.
#include <cstdint>

namespace strata::image {

// ACES filmic curve, Krzysztof Narkowicz's fit; maps [0, inf) onto [0, 1].
float aces_narkowicz(float x);
// sRGB opto-electronic transfer function (IEC 61966-2-1) on [0, 1].
float srgb_oetf(float linear);
// One finite linear channel value to an 8-bit sRGB code: scale (2^stops), ACES, sRGB, round.
uint8_t tonemap_to_srgb8(float linear, float exposure_scale);

}  // namespace strata::image
