// RAW_RGBA16F: width * height * 4 IEEE halfs, little-endian, row-major, top row first.
#include <bit>
#include <cstring>
#include <string>

#include <Imath/half.h>

#include "image/image.h"

namespace strata::image {

static_assert(std::endian::native == std::endian::little, "RAW_RGBA16F is written in the host's byte order");

std::vector<uint8_t> encode_rgba16f(const Image& img) {
  std::vector<uint8_t> out(img.rgba.size() * 2);
  for (size_t i = 0; i < img.rgba.size(); ++i) {
    const uint16_t h = Imath::half(img.rgba[i]).bits();  // the conversion OpenEXR uses, so RAW and EXR agree
    std::memcpy(&out[2 * i], &h, 2);
  }
  return out;
}

Image decode_rgba16f(std::span<const uint8_t> bytes, uint32_t width, uint32_t height) {
  const size_t values = size_t(width) * height * 4;
  if (bytes.size() != values * 2)
    throw ImageError("RAW_RGBA16F image of " + std::to_string(width) + "x" + std::to_string(height) + " needs " +
                     std::to_string(values * 2) + " bytes, got " + std::to_string(bytes.size()));
  Image img;
  img.width = width;
  img.height = height;
  img.rgba.resize(values);
  for (size_t i = 0; i < values; ++i) {
    uint16_t h;
    std::memcpy(&h, bytes.data() + 2 * i, 2);
    Imath::half value;
    value.setBits(h);
    img.rgba[i] = float(value);
  }
  return img;
}

}  // namespace strata::image
