#include "service/encoding.h"

#include <bit>
#include <chrono>
#include <cstring>
#include <stdexcept>
#include <string>

#include <Imath/half.h>
#include <glm/gtc/packing.hpp>

namespace strata::service {

static_assert(std::endian::native == std::endian::little, "RAW_RGBA16F is written in the host's byte order");

std::vector<uint8_t> encode_rgba16f(const image::Image& img) {
  std::vector<uint8_t> out(img.rgba.size() * 2);
  for (size_t i = 0; i < img.rgba.size(); ++i) {
    const uint16_t h = Imath::half(img.rgba[i]).bits();  // the conversion OpenEXR uses, so RAW and EXR agree
    std::memcpy(&out[2 * i], &h, 2);
  }
  return out;
}

image::Image decode_rgba16f(const std::vector<uint8_t>& bytes, uint32_t width, uint32_t height) {
  const size_t values = size_t(width) * height * 4;
  if (bytes.size() != values * 2)
    throw std::invalid_argument("RAW_RGBA16F image of " + std::to_string(width) + "x" + std::to_string(height) + " needs " +
                                std::to_string(values * 2) + " bytes, got " + std::to_string(bytes.size()));
  image::Image img;
  img.width = width;
  img.height = height;
  img.rgba.resize(values);
  for (size_t i = 0; i < values; ++i) {
    uint16_t h;
    std::memcpy(&h, &bytes[2 * i], 2);
    img.rgba[i] = glm::unpackHalf1x16(h);
  }
  return img;
}

v1::Image encode_image(const image::Image& img, v1::ImageEncoding encoding, float exposure) {
  const auto t0 = std::chrono::steady_clock::now();
  std::vector<uint8_t> bytes;
  switch (encoding) {
    case v1::IMAGE_ENCODING_EXR_HALF: bytes = image::encode_exr(img); break;
    case v1::IMAGE_ENCODING_RAW_RGBA16F: bytes = encode_rgba16f(img); break;
    case v1::IMAGE_ENCODING_PNG_PREVIEW: bytes = image::encode_png_preview(img, exposure); break;
    default: throw std::invalid_argument("encoding " + std::to_string(int(encoding)) + " is not an image encoding");
  }
  v1::Image out;
  out.set_encoding(encoding);
  out.set_width(img.width);
  out.set_height(img.height);
  out.set_data(reinterpret_cast<const char*>(bytes.data()), bytes.size());
  out.set_encode_ms(std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count());
  return out;
}

}  // namespace strata::service
