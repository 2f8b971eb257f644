#pragma once
// Decoding the images scenes bring: PNG and JPEG textures to 8-bit RGBA, and Radiance .hdr to
// linear float RGB, with stb_image (Debian's libstb, the decoder tinygltf itself uses). The format
// is told by the file's magic number, never by its name or MIME type, and only PNG, JPEG and
// Radiance HDR reach the decoder; the dimensions are read from the header and checked against the
// caller's limit before a texel is decoded.
#include <cstdint>
#include <span>
#include <string>
#include <vector>

#include "image/image.h"

namespace strata::image {

enum class EncodedFormat { kPng, kJpeg, kRadianceHdr, kOpenExr, kOther };

EncodedFormat sniff_format(std::span<const uint8_t> bytes);
// "a GIF image", "a KTX2 texture", "bytes starting 00 01 02 03": what a refused file is.
std::string describe_encoded(std::span<const uint8_t> bytes);

struct ImageSize {
  uint32_t width = 0;
  uint32_t height = 0;
};
// The size a PNG, JPEG or Radiance HDR header declares. Throws ImageError for other formats and
// for headers that do not parse.
ImageSize encoded_size(std::span<const uint8_t> bytes);

// 8-bit RGBA, row-major with the top row first; texel = R | G << 8 | B << 16 | A << 24 (the byte
// order of VK_FORMAT_R8G8B8A8 and GLSL's unpackUnorm4x8). Grey and RGB images get A = 255;
// 16-bit PNGs are reduced to 8 bits.
struct Rgba8Image {
  uint32_t width = 0;
  uint32_t height = 0;
  std::vector<uint32_t> texels;
};

// A PNG or JPEG, refusing any other format and any side longer than `max_dimension`.
Rgba8Image decode_rgba8(std::span<const uint8_t> bytes, uint32_t max_dimension);

// A Radiance .hdr as linear RGBA floats (A = 1), refusing sides longer than `max_dimension`.
Image decode_radiance_hdr(std::span<const uint8_t> bytes, uint32_t max_dimension);

}  // namespace strata::image
