// Reading EXR files that strata did not write: RGB only, FLOAT samples, offset data windows.
// The files are assembled byte by byte from the OpenEXR file layout so that the reader is checked
// against the format itself, not against our own writer.
#include <cstring>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "image/image.h"

namespace strata::image {
namespace {

class ExrBuilder {
 public:
  void bytes(const void* p, size_t n) {
    const auto* b = static_cast<const uint8_t*>(p);
    out.insert(out.end(), b, b + n);
  }
  void i32(int32_t v) { bytes(&v, 4); }  // EXR is little-endian, like the machines we run on
  void u64(uint64_t v) { bytes(&v, 8); }
  void f32(float v) { bytes(&v, 4); }
  void str(const std::string& s) { bytes(s.c_str(), s.size() + 1); }
  void attribute(const std::string& name, const std::string& type, int32_t size) {
    str(name);
    str(type);
    i32(size);
  }
  std::vector<uint8_t> out;
};

// An uncompressed scanline file with FLOAT channels `names` (sorted, as EXR requires) over the
// data window [x0, x0+w) x [y0, y0+h); sample(channel, x, y) gives each value.
template <typename F>
std::vector<uint8_t> make_exr(const std::vector<std::string>& names, int32_t x0, int32_t y0,
                              int32_t w, int32_t h, F sample) {
  ExrBuilder b;
  b.bytes("\x76\x2f\x31\x01", 4);
  b.i32(2);  // version 2, single-part scanline
  int32_t chlist_size = 1;
  for (const std::string& n : names) chlist_size += int32_t(n.size()) + 1 + 16;
  b.attribute("channels", "chlist", chlist_size);
  for (const std::string& n : names) {
    b.str(n);
    b.i32(2);  // FLOAT
    b.i32(0);  // pLinear and reserved bytes
    b.i32(1);
    b.i32(1);
  }
  b.bytes("", 1);
  b.attribute("compression", "compression", 1);
  b.bytes("", 1);  // NO_COMPRESSION
  for (const char* window : {"dataWindow", "displayWindow"}) {
    b.attribute(window, "box2i", 16);
    b.i32(x0);
    b.i32(y0);
    b.i32(x0 + w - 1);
    b.i32(y0 + h - 1);
  }
  b.attribute("lineOrder", "lineOrder", 1);
  b.bytes("", 1);  // INCREASING_Y
  b.attribute("pixelAspectRatio", "float", 4);
  b.f32(1.0f);
  b.attribute("screenWindowCenter", "v2f", 8);
  b.f32(0.0f);
  b.f32(0.0f);
  b.attribute("screenWindowWidth", "float", 4);
  b.f32(1.0f);
  b.bytes("", 1);  // end of header
  const int32_t line_bytes = w * int32_t(names.size()) * 4;
  const uint64_t first = b.out.size() + 8 * size_t(h);
  for (int32_t y = 0; y < h; ++y) b.u64(first + uint64_t(y) * uint64_t(8 + line_bytes));
  for (int32_t y = 0; y < h; ++y) {
    b.i32(y0 + y);
    b.i32(line_bytes);
    for (size_t c = 0; c < names.size(); ++c) {
      for (int32_t x = 0; x < w; ++x) b.f32(sample(c, x, y));
    }
  }
  return b.out;
}

float value(size_t channel, int32_t x, int32_t y) { return float(channel) + 0.25f * float(x + 4 * y); }

TEST(ExrForeign, RgbWithoutAlphaReadsOpaque) {
  const auto bytes = make_exr({"B", "G", "R"}, 0, 0, 3, 2, value);
  const Image img = decode_exr(bytes);
  ASSERT_EQ(img.width, 3u);
  ASSERT_EQ(img.height, 2u);
  for (int32_t y = 0; y < 2; ++y) {
    for (int32_t x = 0; x < 3; ++x) {
      const float* p = img.pixel(uint32_t(x), uint32_t(y));
      EXPECT_EQ(p[0], value(2, x, y));  // R is the third channel in sorted order
      EXPECT_EQ(p[1], value(1, x, y));
      EXPECT_EQ(p[2], value(0, x, y));
      EXPECT_EQ(p[3], 1.0f);
    }
  }
}

TEST(ExrForeign, OffsetDataWindowStartsAtItsCorner) {
  const auto bytes = make_exr({"A", "B", "G", "R"}, -7, 12, 2, 2, value);
  const Image img = decode_exr(bytes);
  ASSERT_EQ(img.width, 2u);
  ASSERT_EQ(img.height, 2u);
  EXPECT_EQ(img.pixel(0, 0)[3], value(0, 0, 0));
  EXPECT_EQ(img.pixel(1, 1)[0], value(3, 1, 1));
}

TEST(ExrForeign, MissingColourChannelsReadAsZero) {
  const auto bytes = make_exr({"G"}, 0, 0, 2, 1, value);
  const Image img = decode_exr(bytes);
  EXPECT_EQ(img.pixel(1, 0)[0], 0.0f);
  EXPECT_EQ(img.pixel(1, 0)[1], value(0, 1, 0));
  EXPECT_EQ(img.pixel(1, 0)[2], 0.0f);
  EXPECT_EQ(img.pixel(1, 0)[3], 1.0f);
}

TEST(ExrForeign, NoColourChannelIsAnError) {
  const auto bytes = make_exr({"Z"}, 0, 0, 2, 1, value);
  EXPECT_THROW(decode_exr(bytes), ImageError);
  const std::vector<Channel> extra = decode_exr_extra_channels(make_exr({"R", "Z"}, 0, 0, 2, 1, value));
  ASSERT_EQ(extra.size(), 1u);
  EXPECT_EQ(extra[0].name, "Z");
  EXPECT_EQ(extra[0].values, (std::vector<float>{value(1, 0, 0), value(1, 1, 0)}));
}

}  // namespace
}  // namespace strata::image
