// Tonemapped 8-bit PNG previews through libpng's simplified API, which reports errors in the
// png_image struct instead of longjmp-ing through C++ frames.
#include <bit>
#include <climits>
#include <cmath>
#include <cstring>
#include <string>

#include <png.h>

#include "image/image.h"
#include "image/image_util.h"
#include "image/tonemap.h"

namespace strata::image {
namespace {

// Frees libpng's read state on every path out of decode_png, including exceptions.
struct PngImageGuard {
  png_image& image;
  ~PngImageGuard() { png_image_free(&image); }
};

std::string png_message(const png_image& image) { return image.message; }

}  // namespace

namespace {

// An 8-bit PNG of `channels` bytes per pixel (PNG_FORMAT_RGB or PNG_FORMAT_RGBA), top row first.
std::vector<uint8_t> encode_png8(const uint8_t* pixels, size_t bytes, uint32_t width, uint32_t height, uint32_t channels,
                                 const char* what) {
  // libpng takes the row stride as a signed 32-bit value.
  if (width == 0 || height == 0 || width > INT_MAX / channels || height > INT_MAX || bytes != size_t(width) * height * channels) {
    throw ImageError(std::string(what) + ": " + std::to_string(bytes) + " bytes for an image of " + std::to_string(width) + "x" +
                     std::to_string(height) + " (" + std::to_string(channels) + " per pixel, within the PNG writer's limits)");
  }
  png_image image;
  std::memset(&image, 0, sizeof(image));
  image.version = PNG_IMAGE_VERSION;
  image.width = width;
  image.height = height;
  image.format = channels == 4 ? PNG_FORMAT_RGBA : PNG_FORMAT_RGB;
  PngImageGuard guard{image};
  const png_int_32 stride = static_cast<png_int_32>(channels * width);
  // First call sizes the output, second call writes it.
  png_alloc_size_t size = 0;
  if (!png_image_write_to_memory(&image, nullptr, &size, 0, pixels, stride, nullptr)) {
    throw ImageError(std::string(what) + ": libpng failed: " + png_message(image));
  }
  std::vector<uint8_t> out(size);
  if (!png_image_write_to_memory(&image, out.data(), &size, 0, pixels, stride, nullptr)) {
    throw ImageError(std::string(what) + ": libpng failed: " + png_message(image));
  }
  out.resize(size);
  return out;
}

}  // namespace

std::vector<uint8_t> encode_png_rgb8(std::span<const uint8_t> rgb, uint32_t width, uint32_t height) {
  return encode_png8(rgb.data(), rgb.size(), width, height, 3, "encode_png_rgb8");
}

std::vector<uint8_t> encode_png_rgba8(std::span<const uint32_t> texels, uint32_t width, uint32_t height) {
  // Each word is R | G << 8 | B << 16 | A << 24: its bytes in memory are R, G, B, A on a
  // little-endian host, which is what PNG_FORMAT_RGBA reads.
  static_assert(std::endian::native == std::endian::little);
  return encode_png8(reinterpret_cast<const uint8_t*>(texels.data()), texels.size() * 4, width, height, 4, "encode_png_rgba8");
}

std::vector<uint8_t> encode_png_preview(const Image& img, float exposure_stops) {
  detail::check_image(img, "encode_png_preview");
  if (!std::isfinite(exposure_stops)) {
    throw ImageError("encode_png_preview: exposure of " + std::to_string(exposure_stops) +
                     " stops is not finite");
  }
  // libpng takes the row stride as a signed 32-bit value.
  if (img.width > INT_MAX / 3 || img.height > INT_MAX) {
    throw ImageError("encode_png_preview: image of " + std::to_string(img.width) + "x" +
                     std::to_string(img.height) + " exceeds the PNG writer's limits");
  }
  const float scale = std::exp2(exposure_stops);
  const size_t pixels = size_t(img.width) * img.height;
  std::vector<uint8_t> rgb(3 * pixels);
  for (size_t i = 0; i < pixels; ++i) {
    const float* p = &img.rgba[4 * i];
    uint8_t* out = &rgb[3 * i];
    if (!std::isfinite(p[0]) || !std::isfinite(p[1]) || !std::isfinite(p[2])) {
      out[0] = 255;
      out[1] = 0;
      out[2] = 255;
      continue;
    }
    for (int c = 0; c < 3; ++c) out[c] = tonemap_to_srgb8(p[c], scale);
  }

  return encode_png_rgb8(rgb, img.width, img.height);
}

void write_png_rgb8(const std::filesystem::path& path, std::span<const uint8_t> rgb, uint32_t width, uint32_t height) {
  detail::write_file_bytes(path, encode_png_rgb8(rgb, width, height), "write_png_rgb8");
}

void write_png_preview(const std::filesystem::path& path, const Image& img, float exposure_stops) {
  detail::write_file_bytes(path, encode_png_preview(img, exposure_stops), "write_png_preview");
}

Image decode_png(std::span<const uint8_t> bytes) {
  png_image image;
  std::memset(&image, 0, sizeof(image));
  image.version = PNG_IMAGE_VERSION;
  PngImageGuard guard{image};
  if (!png_image_begin_read_from_memory(&image, bytes.data(), bytes.size())) {
    throw ImageError("decode_png: " + png_message(image));
  }
  if (image.width == 0 || image.height == 0) throw ImageError("decode_png: zero-size image");
  // Whatever the stored layout, ask libpng for 8-bit RGBA (opaque alpha when the file has none).
  image.format = PNG_FORMAT_RGBA;
  std::vector<uint8_t> rgba8(PNG_IMAGE_SIZE(image));
  if (!png_image_finish_read(&image, nullptr, rgba8.data(), 0, nullptr)) {
    throw ImageError("decode_png: " + png_message(image));
  }
  Image img{image.width, image.height, std::vector<float>(rgba8.size())};
  for (size_t i = 0; i < rgba8.size(); ++i) img.rgba[i] = float(rgba8[i]) / 255.0f;
  return img;
}

}  // namespace strata::image
