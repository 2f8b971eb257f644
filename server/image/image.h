#pragma once
// HDR images on the host: EXR (half RGBA plus optional single-channel AOVs) and tonemapped PNG.
#include <cstdint>
#include <filesystem>
#include <span>
#include <stdexcept>
#include <string>
#include <vector>

namespace strata::image {

struct ImageError : std::runtime_error {
  using std::runtime_error::runtime_error;
};

// Linear RGBA, 32-bit float, row-major with the top row first.
struct Image {
  uint32_t width = 0;
  uint32_t height = 0;
  std::vector<float> rgba;  // 4 * width * height
  float* pixel(uint32_t x, uint32_t y) { return &rgba[4 * (size_t(y) * width + x)]; }
  const float* pixel(uint32_t x, uint32_t y) const { return &rgba[4 * (size_t(y) * width + x)]; }
};

// An extra EXR channel (an AOV such as depth or a domain count): width * height floats.
struct Channel {
  std::string name;
  std::vector<float> values;
};

// EXR with HALF R, G, B, A (and each extra channel as FLOAT), ZIP compression.
std::vector<uint8_t> encode_exr(const Image& img, std::span<const Channel> extra = {});
void write_exr(const std::filesystem::path& path, const Image& img, std::span<const Channel> extra = {});
// Reads R, G, B (and A, else 1) of any EXR; throws ImageError naming the file on failure.
Image read_exr(const std::filesystem::path& path);
Image decode_exr(std::span<const uint8_t> bytes);
// Every channel other than R, G, B, A (the AOVs written as `extra`) as floats, sorted by name
// (EXR keeps its channel list sorted).
std::vector<Channel> decode_exr_extra_channels(std::span<const uint8_t> bytes);

// RAW_RGBA16F: 4 IEEE halfs per pixel (rounded as OpenEXR rounds), little-endian, top row first.
std::vector<uint8_t> encode_rgba16f(const Image& img);
// The inverse; throws ImageError when the byte count does not match width x height.
Image decode_rgba16f(std::span<const uint8_t> bytes, uint32_t width, uint32_t height);

// An 8-bit RGB PNG of `rgb` (3 bytes per pixel, top row first); throws ImageError on a size mismatch.
std::vector<uint8_t> encode_png_rgb8(std::span<const uint8_t> rgb, uint32_t width, uint32_t height);
void write_png_rgb8(const std::filesystem::path& path, std::span<const uint8_t> rgb, uint32_t width, uint32_t height);
// An 8-bit RGBA PNG of RGBA8 words (R | G << 8 | B << 16 | A << 24, top row first), as textures hold them.
std::vector<uint8_t> encode_png_rgba8(std::span<const uint32_t> texels, uint32_t width, uint32_t height);
// 8-bit sRGB PNG preview: exposure (stops) then the ACES filmic curve (Narkowicz fit), then sRGB OETF.
// Non-finite pixels are written magenta so that they cannot go unnoticed.
std::vector<uint8_t> encode_png_preview(const Image& img, float exposure_stops = 0.0f);
void write_png_preview(const std::filesystem::path& path, const Image& img, float exposure_stops = 0.0f);
// Decodes an 8-bit RGB/RGBA PNG to linear-free values in [0,1] (no inverse tonemap); for tests.
Image decode_png(std::span<const uint8_t> bytes);

}  // namespace strata::image
