#include "http/frame_jpeg.h"

#include <cmath>
#include <csetjmp>
#include <cstdio>
#include <string>

#include <jpeglib.h>

#include "image/tonemap.h"

namespace strata::http {
namespace {

// libjpeg reports errors through a callback that must not return: it jumps back to the caller.
struct ErrorManager {
  jpeg_error_mgr pub;
  std::jmp_buf jump;
  char message[JMSG_LENGTH_MAX] = {};
};

void on_error(j_common_ptr info) {
  auto* err = reinterpret_cast<ErrorManager*>(info->err);
  (*info->err->format_message)(info, err->message);
  std::longjmp(err->jump, 1);
}

}  // namespace

std::vector<uint8_t> encode_jpeg_preview(const image::Image& img, float exposure_stops, int quality) {
  if (img.width == 0 || img.height == 0 || img.rgba.size() != size_t(img.width) * img.height * 4)
    throw image::ImageError("encode_jpeg_preview: the image is empty or its pixel count does not match " +
                            std::to_string(img.width) + "x" + std::to_string(img.height));
  if (img.width > JPEG_MAX_DIMENSION || img.height > JPEG_MAX_DIMENSION)
    throw image::ImageError("encode_jpeg_preview: " + std::to_string(img.width) + "x" + std::to_string(img.height) +
                            " exceeds JPEG's " + std::to_string(JPEG_MAX_DIMENSION) + " pixels per side");
  if (!std::isfinite(exposure_stops))
    throw image::ImageError("encode_jpeg_preview: exposure of " + std::to_string(exposure_stops) + " stops is not finite");
  const float scale = std::exp2(exposure_stops);
  std::vector<uint8_t> row(size_t(img.width) * 3);

  jpeg_compress_struct info{};
  ErrorManager err;
  info.err = jpeg_std_error(&err.pub);
  err.pub.error_exit = on_error;
  unsigned char* out = nullptr;
  unsigned long out_size = 0;
  if (setjmp(err.jump)) {
    jpeg_destroy_compress(&info);
    std::free(out);
    throw image::ImageError(std::string("encode_jpeg_preview: libjpeg: ") + err.message);
  }
  jpeg_create_compress(&info);
  jpeg_mem_dest(&info, &out, &out_size);
  info.image_width = img.width;
  info.image_height = img.height;
  info.input_components = 3;
  info.in_color_space = JCS_RGB;
  jpeg_set_defaults(&info);
  jpeg_set_quality(&info, quality, TRUE);
  info.dct_method = JDCT_ISLOW;
  jpeg_start_compress(&info, TRUE);
  for (uint32_t y = 0; y < img.height; ++y) {
    for (uint32_t x = 0; x < img.width; ++x) {
      const float* p = img.pixel(x, y);
      uint8_t* o = &row[size_t(x) * 3];
      if (!std::isfinite(p[0]) || !std::isfinite(p[1]) || !std::isfinite(p[2])) {
        o[0] = 255, o[1] = 0, o[2] = 255;
        continue;
      }
      for (int c = 0; c < 3; ++c) o[c] = image::tonemap_to_srgb8(p[c], scale);
    }
    JSAMPROW rows[1] = {row.data()};
    jpeg_write_scanlines(&info, rows, 1);
  }
  jpeg_finish_compress(&info);
  jpeg_destroy_compress(&info);
  std::vector<uint8_t> bytes(out, out + out_size);
  std::free(out);
  return bytes;
}

}  // namespace strata::http
