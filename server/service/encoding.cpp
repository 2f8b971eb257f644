#include "service/encoding.h"

#include <algorithm>
#include <chrono>
#include <cstring>
#include <stdexcept>
#include <string>


namespace strata::service {


v1::Image encode_image(const image::Image& img, v1::ImageEncoding encoding, float exposure) {
  const auto t0 = std::chrono::steady_clock::now();
  std::vector<uint8_t> bytes;
  switch (encoding) {
    case v1::IMAGE_ENCODING_EXR_HALF: bytes = image::encode_exr(img); break;
    case v1::IMAGE_ENCODING_RAW_RGBA16F: bytes = image::encode_rgba16f(img); break;
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

v1::Image encode_domain_map(const render::DomainMap& map) {
  const auto t0 = std::chrono::steady_clock::now();
  const std::vector<uint8_t> bytes = image::encode_png_rgb8(render::domain_map_rgb(map), map.width, map.height);
  v1::Image out;
  out.set_encoding(v1::IMAGE_ENCODING_DOMAIN_MAP);
  out.set_width(map.width);
  out.set_height(map.height);
  out.set_data(reinterpret_cast<const char*>(bytes.data()), bytes.size());
  out.set_encode_ms(std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count());
  return out;
}

}  // namespace strata::service
