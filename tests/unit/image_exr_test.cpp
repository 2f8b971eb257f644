// EXR encode/decode: half-precision colour, exact FLOAT AOVs, files on disk.
#include <cmath>
#include <filesystem>
#include <string>
#include <unistd.h>

#include <gtest/gtest.h>

#include "image/image.h"

namespace strata::image {
namespace {

// A ramp over several decades with both signs, so that the half conversion is exercised at
// different exponents; the channels differ so that a channel mix-up cannot pass.
Image make_ramp(uint32_t w, uint32_t h) {
  Image img{w, h, std::vector<float>(4 * size_t(w) * h)};
  for (uint32_t y = 0; y < h; ++y) {
    for (uint32_t x = 0; x < w; ++x) {
      float* p = img.pixel(x, y);
      const float t = float(y * w + x) / float(w * h);
      p[0] = std::exp2(-10.0f + 20.0f * t);
      p[1] = -0.5f * std::exp2(-5.0f + 10.0f * t);
      p[2] = 1.0f / 3.0f + float(x);
      p[3] = t;
    }
  }
  return img;
}

void expect_close(float expected, float actual, float rel) {
  EXPECT_LE(std::abs(actual - expected), rel * std::abs(expected) + 1e-7f)
      << "expected " << expected << ", got " << actual;
}

std::filesystem::path temp_path(const std::string& name) {
  return std::filesystem::temp_directory_path() /
         ("strata_" + std::to_string(::getpid()) + "_" + name);
}

TEST(ExrRoundTrip, ColourWithinHalfPrecision) {
  const Image img = make_ramp(17, 9);
  const std::vector<uint8_t> bytes = encode_exr(img);
  const Image back = decode_exr(bytes);
  ASSERT_EQ(back.width, img.width);
  ASSERT_EQ(back.height, img.height);
  ASSERT_EQ(back.rgba.size(), img.rgba.size());
  for (size_t i = 0; i < img.rgba.size(); ++i) expect_close(img.rgba[i], back.rgba[i], 1e-3f);
}

TEST(ExrRoundTrip, ColourIsStoredAsHalf) {
  Image img{1, 1, {1.0f / 3.0f, 1.0f / 3.0f, 1.0f / 3.0f, 1.0f}};
  const Image back = decode_exr(encode_exr(img));
  // 1/3 needs more than half's 11 significant bits, so HALF storage rounds it.
  EXPECT_NE(back.rgba[0], img.rgba[0]);
  expect_close(img.rgba[0], back.rgba[0], 1e-3f);
}

TEST(ExrRoundTrip, ExtraChannelsAreExactFloats) {
  const Image img = make_ramp(5, 4);
  std::vector<Channel> extra = {{"depth", {}}, {"domains.count", {}}};
  for (size_t i = 0; i < 20; ++i) {
    extra[0].values.push_back(1.0f / 3.0f + 1e6f * float(i));  // beyond half's range and precision
    extra[1].values.push_back(float(i));
  }
  const std::vector<uint8_t> bytes = encode_exr(img, extra);
  const std::vector<Channel> back = decode_exr_extra_channels(bytes);
  ASSERT_EQ(back.size(), 2u);
  EXPECT_EQ(back[0].name, "depth");
  EXPECT_EQ(back[0].values, extra[0].values);
  EXPECT_EQ(back[1].name, "domains.count");
  EXPECT_EQ(back[1].values, extra[1].values);
  // The colour channels are unaffected by the AOVs next to them.
  const Image colour = decode_exr(bytes);
  for (size_t i = 0; i < img.rgba.size(); ++i) expect_close(img.rgba[i], colour.rgba[i], 1e-3f);
}

TEST(ExrRoundTrip, NoExtraChannelsWhenNoneWritten) {
  EXPECT_TRUE(decode_exr_extra_channels(encode_exr(make_ramp(3, 2))).empty());
}

TEST(ExrRoundTrip, TopRowComesFirst) {
  Image img{1, 2, {1.0f, 0.0f, 0.0f, 1.0f, 0.0f, 0.0f, 1.0f, 1.0f}};
  const Image back = decode_exr(encode_exr(img));
  EXPECT_EQ(back.pixel(0, 0)[0], 1.0f);
  EXPECT_EQ(back.pixel(0, 1)[2], 1.0f);
}

TEST(ExrRoundTrip, FileOnDisk) {
  const std::filesystem::path path = temp_path("roundtrip.exr");
  const Image img = make_ramp(8, 8);
  write_exr(path, img, std::vector<Channel>{{"depth", std::vector<float>(64, 2.5f)}});
  const Image back = read_exr(path);
  std::filesystem::remove(path);
  ASSERT_EQ(back.width, 8u);
  ASSERT_EQ(back.height, 8u);
  for (size_t i = 0; i < img.rgba.size(); ++i) expect_close(img.rgba[i], back.rgba[i], 1e-3f);
}

TEST(ExrRoundTrip, ZipCompressesSmoothImages) {
  // A constant image compresses far below its raw half size (8 bytes per pixel).
  Image img{64, 64, std::vector<float>(4 * 64 * 64, 0.25f)};
  EXPECT_LT(encode_exr(img).size(), 64u * 64u * 8u / 4u);
}

}  // namespace
}  // namespace strata::image
