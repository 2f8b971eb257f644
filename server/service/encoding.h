#pragma once
// Frame images in the encodings clients ask for.
#include <cstdint>
#include <vector>

#include "image/image.h"
#include "strata/v1/render.pb.h"

namespace strata::service {

// width*height*4 IEEE halfs (rounded as OpenEXR rounds), little-endian, row-major, top row first.
std::vector<uint8_t> encode_rgba16f(const image::Image& img);
// The inverse (for clients and tests); throws std::invalid_argument when the size does not match.
image::Image decode_rgba16f(const std::vector<uint8_t>& bytes, uint32_t width, uint32_t height);

// Encodes `img`; `exposure` (stops) applies to PNG previews. Fills encode_ms with the CPU time spent.
::strata::v1::Image encode_image(const image::Image& img, ::strata::v1::ImageEncoding encoding, float exposure);

}  // namespace strata::service
