// Every failure of the image codecs is an ImageError that says what failed and on which file.
#include <cmath>
#include <filesystem>
#include <fstream>
#include <string>
#include <unistd.h>

#include <gtest/gtest.h>

#include "image/image.h"

namespace strata::image {
namespace {

Image small_image() { return Image{4, 3, std::vector<float>(48, 0.5f)}; }

// Runs f, expects an ImageError, and returns its message.
template <typename F>
std::string error_of(F&& f) {
  try {
    f();
  } catch (const ImageError& e) {
    return e.what();
  } catch (const std::exception& e) {
    ADD_FAILURE() << "wrong exception type: " << e.what();
    return {};
  }
  ADD_FAILURE() << "no exception";
  return {};
}

TEST(ImageErrors, MissingFileIsNamed) {
  const std::string path = "/nonexistent/strata/frame.exr";
  const std::string message = error_of([&] { read_exr(path); });
  EXPECT_NE(message.find(path), std::string::npos) << message;
}

TEST(ImageErrors, TruncatedExrBytes) {
  const std::vector<uint8_t> bytes = encode_exr(small_image());
  for (size_t size : {size_t(0), size_t(3), size_t(8), bytes.size() / 2, bytes.size() - 1}) {
    const std::span<const uint8_t> truncated(bytes.data(), size);
    EXPECT_FALSE(error_of([&] { decode_exr(truncated); }).empty()) << size << " bytes";
  }
}

TEST(ImageErrors, TruncatedExrFileIsNamed) {
  const std::vector<uint8_t> bytes = encode_exr(small_image());
  const std::filesystem::path path = std::filesystem::temp_directory_path() /
                                     ("strata_" + std::to_string(::getpid()) + "_truncated.exr");
  {
    std::ofstream out(path, std::ios::binary);
    out.write(reinterpret_cast<const char*>(bytes.data()), std::streamsize(bytes.size() / 2));
  }
  const std::string message = error_of([&] { read_exr(path); });
  std::filesystem::remove(path);
  EXPECT_NE(message.find(path.string()), std::string::npos) << message;
}

TEST(ImageErrors, NotAnImage) {
  const std::vector<uint8_t> garbage(100, 0x5a);
  EXPECT_FALSE(error_of([&] { decode_exr(garbage); }).empty());
  EXPECT_FALSE(error_of([&] { decode_png(garbage); }).empty());
}

TEST(ImageErrors, ZeroSizeIsRejected) {
  for (const Image& img : {Image{0, 0, {}}, Image{0, 3, {}}, Image{3, 0, {}}}) {
    EXPECT_NE(error_of([&] { encode_exr(img); }).find("zero size"), std::string::npos);
    EXPECT_NE(error_of([&] { encode_png_preview(img); }).find("zero size"), std::string::npos);
  }
}

TEST(ImageErrors, RgbaSizeMismatchIsRejected) {
  Image img = small_image();
  img.rgba.pop_back();
  EXPECT_FALSE(error_of([&] { encode_exr(img); }).empty());
  EXPECT_FALSE(error_of([&] { encode_png_preview(img); }).empty());
}

TEST(ImageErrors, BadExtraChannels) {
  const Image img = small_image();
  const std::vector<Channel> wrong_size = {{"depth", std::vector<float>(11)}};
  const std::vector<Channel> colour_name = {{"G", std::vector<float>(12)}};
  const std::vector<Channel> duplicate = {{"d", std::vector<float>(12)}, {"d", std::vector<float>(12)}};
  EXPECT_NE(error_of([&] { encode_exr(img, wrong_size); }).find("depth"), std::string::npos);
  EXPECT_FALSE(error_of([&] { encode_exr(img, colour_name); }).empty());
  EXPECT_FALSE(error_of([&] { encode_exr(img, duplicate); }).empty());
}

TEST(ImageErrors, NonFiniteExposure) {
  EXPECT_FALSE(error_of([&] { encode_png_preview(small_image(), NAN); }).empty());
}

TEST(ImageErrors, UnwritablePathIsNamed) {
  const std::string path = "/nonexistent/strata/frame.png";
  EXPECT_NE(error_of([&] { write_png_preview(path, small_image()); }).find(path), std::string::npos);
}

}  // namespace
}  // namespace strata::image
