#pragma once
// The viewer's frames: the linear image tonemapped as the PNG preview is (exposure, ACES filmic,
// sRGB; image/tonemap.h) and compressed with libjpeg-turbo (Debian's libjpeg62-turbo).
#include <cstdint>
#include <vector>

#include "image/image.h"

namespace strata::http {

constexpr int k_jpeg_quality = 85;

// Baseline JPEG, 4:2:0, at `quality` (1..100). Non-finite pixels come out magenta, as in the PNG
// preview, so that they cannot go unnoticed. Throws image::ImageError for an empty image or a
// non-finite exposure.
std::vector<uint8_t> encode_jpeg_preview(const image::Image& img, float exposure_stops, int quality = k_jpeg_quality);

}  // namespace strata::http
