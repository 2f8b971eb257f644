// PNG previews: sizes, the tonemap curve, exposure, and magenta for non-finite pixels.
#include <cmath>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <limits>
#include <unistd.h>

#include <gtest/gtest.h>

#include "image/image.h"
#include "image/tonemap.h"

namespace strata::image {
namespace {

Image constant_image(uint32_t w, uint32_t h, float value) {
  Image img{w, h, std::vector<float>(4 * size_t(w) * h, value)};
  return img;
}

TEST(PngPreview, KeepsSizeAndIsOpaque) {
  const Image img = constant_image(7, 3, 0.5f);
  const Image back = decode_png(encode_png_preview(img));
  ASSERT_EQ(back.width, 7u);
  ASSERT_EQ(back.height, 3u);
  ASSERT_EQ(back.rgba.size(), 4u * 7u * 3u);
  for (uint32_t y = 0; y < 3; ++y) {
    for (uint32_t x = 0; x < 7; ++x) EXPECT_EQ(back.pixel(x, y)[3], 1.0f);
  }
}

TEST(PngPreview, PixelsAreTheTonemappedValues) {
  Image img = constant_image(16, 2, 0.0f);
  for (uint32_t x = 0; x < 16; ++x) {
    float* p = img.pixel(x, 1);  // bottom row only: rows must not be swapped
    p[0] = 0.01f * float(x * x);
    p[1] = 0.5f * float(x);
    p[2] = -1.0f;
  }
  const float stops = 1.5f;
  const Image back = decode_png(encode_png_preview(img, stops));
  for (uint32_t x = 0; x < 16; ++x) {
    for (int c = 0; c < 3; ++c) {
      const float expected = float(tonemap_to_srgb8(img.pixel(x, 1)[c], std::exp2(stops))) / 255.0f;
      EXPECT_EQ(back.pixel(x, 1)[c], expected) << "x " << x << " channel " << c;
      EXPECT_EQ(back.pixel(x, 0)[c], 0.0f);
    }
  }
}

TEST(PngPreview, OneStopDoublesTheInput) {
  const Image half_bright = decode_png(encode_png_preview(constant_image(2, 2, 0.3f), 1.0f));
  const Image full = decode_png(encode_png_preview(constant_image(2, 2, 0.6f), 0.0f));
  EXPECT_EQ(half_bright.rgba, full.rgba);
}

TEST(PngPreview, NonFinitePixelsAreMagenta) {
  Image img = constant_image(4, 1, 0.2f);
  img.pixel(0, 0)[0] = std::numeric_limits<float>::quiet_NaN();
  img.pixel(1, 0)[1] = std::numeric_limits<float>::infinity();
  img.pixel(2, 0)[2] = -std::numeric_limits<float>::infinity();
  const Image back = decode_png(encode_png_preview(img));
  for (uint32_t x = 0; x < 3; ++x) {
    EXPECT_EQ(back.pixel(x, 0)[0], 1.0f) << x;
    EXPECT_EQ(back.pixel(x, 0)[1], 0.0f) << x;
    EXPECT_EQ(back.pixel(x, 0)[2], 1.0f) << x;
  }
  // A finite grey neighbour stays grey.
  EXPECT_EQ(back.pixel(3, 0)[0], back.pixel(3, 0)[1]);
  EXPECT_GT(back.pixel(3, 0)[1], 0.0f);
}

TEST(PngPreview, WritesAFile) {
  const std::filesystem::path path =
      std::filesystem::temp_directory_path() / ("strata_" + std::to_string(::getpid()) + ".png");
  write_png_preview(path, constant_image(5, 4, 1.0f));
  std::ifstream in(path, std::ios::binary);
  const std::vector<uint8_t> bytes{std::istreambuf_iterator<char>(in), {}};
  std::filesystem::remove(path);
  const Image back = decode_png(bytes);
  EXPECT_EQ(back.width, 5u);
  EXPECT_EQ(back.height, 4u);
}

TEST(PngTonemap, KnownValues) {
  EXPECT_EQ(tonemap_to_srgb8(0.0f, 1.0f), 0);
  EXPECT_EQ(tonemap_to_srgb8(-5.0f, 1.0f), 0);
  EXPECT_EQ(tonemap_to_srgb8(1e4f, 1.0f), 255);
  EXPECT_EQ(tonemap_to_srgb8(std::numeric_limits<float>::max(), 1.0f), 255);
  EXPECT_EQ(tonemap_to_srgb8(1.0f, std::numeric_limits<float>::max()), 255);  // overflow to inf
  // ACES(1) = 2.54 / 3.16 = 0.80380; sRGB: 1.055 * 0.80380^(1/2.4) - 0.055 = 0.90823 -> 231.6.
  EXPECT_NEAR(aces_narkowicz(1.0f), 2.54f / 3.16f, 1e-6f);
  EXPECT_EQ(tonemap_to_srgb8(1.0f, 1.0f), 232);
  EXPECT_EQ(tonemap_to_srgb8(0.5f, 2.0f), 232);
  // The linear toe of the sRGB curve.
  EXPECT_NEAR(srgb_oetf(0.002f), 12.92f * 0.002f, 1e-7f);
  EXPECT_NEAR(srgb_oetf(1.0f), 1.0f, 1e-6f);
}

TEST(PngTonemap, Monotone) {
  float previous_curve = -1.0f;
  uint8_t previous_code = 0;
  for (int i = -400; i <= 400; ++i) {
    const float x = std::exp2(float(i) / 20.0f);  // 2^-20 .. 2^20
    const float curve = aces_narkowicz(x);
    EXPECT_GE(curve, previous_curve) << x;
    EXPECT_GE(tonemap_to_srgb8(x, 1.0f), previous_code) << x;
    previous_curve = curve;
    previous_code = tonemap_to_srgb8(x, 1.0f);
  }
  EXPECT_EQ(previous_code, 255);
}

}  // namespace
}  // namespace strata::image
