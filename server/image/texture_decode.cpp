#include "image/texture_decode.h"

#include <algorithm>
#include <climits>
#include <cstdio>
#include <cstring>
#include <memory>
#include <string>
#include <string_view>

#include <stb_image.h>

namespace strata::image {
namespace {

bool starts_with(std::span<const uint8_t> bytes, std::initializer_list<uint8_t> magic) {
  if (bytes.size() < magic.size()) return false;
  return std::equal(magic.begin(), magic.end(), bytes.begin());
}

bool starts_with(std::span<const uint8_t> bytes, const char* text) {
  const size_t n = std::strlen(text);
  return bytes.size() >= n && std::memcmp(bytes.data(), text, n) == 0;
}

int checked_length(std::span<const uint8_t> bytes) {
  if (bytes.empty()) throw ImageError("the image is empty (0 bytes)");
  if (bytes.size() > size_t(INT_MAX))
    throw ImageError("the image is " + std::to_string(bytes.size()) + " bytes; the decoder takes at most 2 GiB");
  return static_cast<int>(bytes.size());
}

std::string failure() {
  const char* reason = stbi_failure_reason();
  return reason != nullptr ? reason : "unknown error";
}

void check_dimensions(ImageSize size, uint32_t max_dimension) {
  if (size.width == 0 || size.height == 0) throw ImageError("the image declares a zero size");
  if (size.width > max_dimension || size.height > max_dimension) {
    throw ImageError("the image is " + std::to_string(size.width) + " x " + std::to_string(size.height) +
                     " texels, over the largest texture dimension (" + std::to_string(max_dimension) + ")");
  }
}

struct StbFree {
  void operator()(void* p) const { stbi_image_free(p); }
};

}  // namespace

EncodedFormat sniff_format(std::span<const uint8_t> bytes) {
  if (starts_with(bytes, {0x89, 'P', 'N', 'G', 0x0D, 0x0A, 0x1A, 0x0A})) return EncodedFormat::kPng;
  if (starts_with(bytes, {0xFF, 0xD8, 0xFF})) return EncodedFormat::kJpeg;
  if (starts_with(bytes, "#?RADIANCE") || starts_with(bytes, "#?RGBE")) return EncodedFormat::kRadianceHdr;
  if (starts_with(bytes, {0x76, 0x2F, 0x31, 0x01})) return EncodedFormat::kOpenExr;
  return EncodedFormat::kOther;
}

std::string describe_encoded(std::span<const uint8_t> bytes) {
  switch (sniff_format(bytes)) {
    case EncodedFormat::kPng: return "a PNG image";
    case EncodedFormat::kJpeg: return "a JPEG image";
    case EncodedFormat::kRadianceHdr: return "a Radiance HDR image";
    case EncodedFormat::kOpenExr: return "an OpenEXR image";
    case EncodedFormat::kOther: break;
  }
  if (bytes.empty()) return "empty (0 bytes)";
  if (starts_with(bytes, "GIF8")) return "a GIF image";
  if (starts_with(bytes, "BM")) return "a BMP image";
  if (starts_with(bytes, "DDS ")) return "a DDS texture";
  if (starts_with(bytes, {0xAB, 'K', 'T', 'X', ' ', '2', '0', 0xBB})) return "a KTX2 texture";
  if (starts_with(bytes, {0xAB, 'K', 'T', 'X', ' ', '1', '1', 0xBB})) return "a KTX texture";
  if (bytes.size() >= 12 && starts_with(bytes, "RIFF") && std::memcmp(bytes.data() + 8, "WEBP", 4) == 0)
    return "a WebP image";
  if (bytes.size() >= 12 && std::memcmp(bytes.data() + 4, "ftypavif", 8) == 0) return "an AVIF image";
  std::string hex = "bytes starting";
  for (size_t i = 0; i < std::min<size_t>(bytes.size(), 4); ++i) {
    char b[4];
    std::snprintf(b, sizeof b, " %02x", bytes[i]);
    hex += b;
  }
  return hex;
}

ImageSize encoded_size(std::span<const uint8_t> bytes) {
  const EncodedFormat format = sniff_format(bytes);
  if (format != EncodedFormat::kPng && format != EncodedFormat::kJpeg && format != EncodedFormat::kRadianceHdr)
    throw ImageError("unsupported image type: " + describe_encoded(bytes));
  int w = 0, h = 0, comp = 0;
  if (stbi_info_from_memory(bytes.data(), checked_length(bytes), &w, &h, &comp) == 0 || w <= 0 || h <= 0)
    throw ImageError("cannot read the " + describe_encoded(bytes).substr(2) + "'s header: " + failure());
  return {static_cast<uint32_t>(w), static_cast<uint32_t>(h)};
}

static void check_png_chunks(std::span<const uint8_t> bytes);

Rgba8Image decode_rgba8(std::span<const uint8_t> bytes, uint32_t max_dimension) {
  const EncodedFormat format = sniff_format(bytes);
  if (format != EncodedFormat::kPng && format != EncodedFormat::kJpeg)
    throw ImageError("unsupported image type: " + describe_encoded(bytes) + " (textures are PNG or JPEG)");
  const ImageSize size = encoded_size(bytes);
  check_dimensions(size, max_dimension);
  if (format == EncodedFormat::kPng) check_png_chunks(bytes);
  int w = 0, h = 0, comp = 0;
  std::unique_ptr<stbi_uc, StbFree> pixels(stbi_load_from_memory(bytes.data(), checked_length(bytes), &w, &h, &comp, 4));
  if (!pixels) throw ImageError("cannot decode the " + describe_encoded(bytes).substr(2) + ": " + failure());
  if (uint32_t(w) != size.width || uint32_t(h) != size.height)
    throw ImageError("the decoded size differs from the header's");
  Rgba8Image out;
  out.width = size.width;
  out.height = size.height;
  out.texels.resize(size_t(size.width) * size.height);
  std::memcpy(out.texels.data(), pixels.get(), out.texels.size() * 4);  // RGBA bytes, little-endian words
  return out;
}

// Walks the new-style run-length scanlines of a Radiance HDR image before stb_image decodes it: the
// stb_image Debian ships loops without end on a run of length 0 (or on data that ends inside a
// scanline, which it reads as zeros), so such a file is refused here, naming the scanline. Flat and
// old-style scanlines, which stb reads with a bounded loop, end the walk.
// Every chunk of a PNG must fit in the bytes given: the stb_image Debian ships reserves the length
// an IDAT chunk claims before reading it, so a few bytes could make it allocate hundreds of MB.
static void check_png_chunks(std::span<const uint8_t> bytes) {
  size_t at = 8;  // the signature
  while (at + 8 <= bytes.size()) {
    const uint64_t length = uint64_t(bytes[at]) << 24 | uint64_t(bytes[at + 1]) << 16 | uint64_t(bytes[at + 2]) << 8 | bytes[at + 3];
    const std::string type(reinterpret_cast<const char*>(bytes.data() + at + 4), 4);
    const uint64_t left = bytes.size() - at;
    if (12 + length > left)
      throw ImageError("the PNG's chunk at byte " + std::to_string(at) + " claims " + std::to_string(length) + " bytes where " +
                       std::to_string(left > 12 ? left - 12 : 0) + " remain");
    if (type == "IEND") return;
    at += 12 + length;
  }
}

static void check_hdr_runs(std::span<const uint8_t> bytes, const ImageSize& size) {
  const std::string_view text(reinterpret_cast<const char*>(bytes.data()), bytes.size());
  // The header ends where stb ends it: at the first line after the signature that is empty or
  // starts with a NUL byte (stb reads the line into a C string).
  size_t line = text.find('\n');
  while (line != std::string_view::npos && line + 1 < text.size() && text[line + 1] != '\n' && text[line + 1] != '\0')
    line = text.find('\n', line + 1);
  if (line == std::string_view::npos || line + 1 >= text.size()) return;  // stb refuses a header without its blank line
  const size_t blank = text.find('\n', line + 1);  // the end of the blank line
  if (blank == std::string_view::npos) return;
  const size_t resolution_end = text.find('\n', blank + 1);
  if (resolution_end == std::string_view::npos) return;
  size_t at = resolution_end + 1;
  const uint32_t width = size.width;
  if (width < 8 || width >= 32768) return;  // stb reads such images flat
  auto byte = [&](uint32_t row) -> uint32_t {
    if (at >= bytes.size())
      throw ImageError("the Radiance HDR image's run-length data ends early (scanline " + std::to_string(row) + ")");
    return bytes[at++];
  };
  for (uint32_t row = 0; row < size.height; ++row) {
    if (bytes.size() - std::min(at, bytes.size()) < 4) throw ImageError("the Radiance HDR image's run-length data ends early (scanline " + std::to_string(row) + ")");
    if (bytes[at] != 2 || bytes[at + 1] != 2 || (bytes[at + 2] & 0x80) != 0) return;  // flat from here on
    if ((uint32_t(bytes[at + 2]) << 8 | bytes[at + 3]) != width) return;  // stb refuses the length itself
    at += 4;
    for (int component = 0; component < 4; ++component)
      for (uint32_t left = width; left > 0;) {
        uint32_t count = byte(row);
        const bool run = count > 128;
        if (run) count -= 128;
        if (count == 0 || count > left)
          throw ImageError("the Radiance HDR image has a run of length " + std::to_string(count) + " in scanline " + std::to_string(row) +
                           " where " + std::to_string(left) + " pixels are left");
        if (run) byte(row);
        else
          for (uint32_t i = 0; i < count; ++i) byte(row);
        left -= count;
      }
  }
}

Image decode_radiance_hdr(std::span<const uint8_t> bytes, uint32_t max_dimension) {
  if (sniff_format(bytes) != EncodedFormat::kRadianceHdr)
    throw ImageError("not a Radiance HDR image: " + describe_encoded(bytes));
  const ImageSize size = encoded_size(bytes);
  check_dimensions(size, max_dimension);
  check_hdr_runs(bytes, size);
  int w = 0, h = 0, comp = 0;
  std::unique_ptr<float, StbFree> pixels(stbi_loadf_from_memory(bytes.data(), checked_length(bytes), &w, &h, &comp, 4));
  if (!pixels) throw ImageError("cannot decode the Radiance HDR image: " + failure());
  if (uint32_t(w) != size.width || uint32_t(h) != size.height)
    throw ImageError("the decoded size differs from the header's");
  Image out;
  out.width = size.width;
  out.height = size.height;
  out.rgba.assign(pixels.get(), pixels.get() + size_t(w) * size_t(h) * 4);
  return out;
}

}  // namespace strata::image
