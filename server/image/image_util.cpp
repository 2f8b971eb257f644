#include "image/image_util.h"

#include <cerrno>
#include <cstring>
#include <fstream>
#include <string>

namespace strata::image::detail {

void check_image(const Image& img, std::string_view what) {
  if (img.width == 0 || img.height == 0) {
    throw ImageError(std::string(what) + ": image has zero size (" + std::to_string(img.width) +
                     "x" + std::to_string(img.height) + ")");
  }
  const size_t expected = 4 * size_t(img.width) * img.height;
  if (img.rgba.size() != expected) {
    throw ImageError(std::string(what) + ": rgba holds " + std::to_string(img.rgba.size()) +
                     " floats, a " + std::to_string(img.width) + "x" + std::to_string(img.height) +
                     " image needs " + std::to_string(expected));
  }
}

std::vector<uint8_t> read_file_bytes(const std::filesystem::path& path, std::string_view what) {
  // Asking the file system first gives a clear message for a missing file or a directory, which
  // an ifstream would open and then report with a nonsense size.
  std::error_code ec;
  const bool regular = std::filesystem::is_regular_file(path, ec);
  const uintmax_t size = regular ? std::filesystem::file_size(path, ec) : 0;
  if (!regular || ec) {
    throw ImageError(std::string(what) + ": cannot read '" + path.string() +
                     "': " + (ec ? ec.message() : std::string("not a regular file")));
  }
  std::vector<uint8_t> bytes(static_cast<size_t>(size));
  std::ifstream in(path, std::ios::binary);
  if (!in || !in.read(reinterpret_cast<char*>(bytes.data()), static_cast<std::streamsize>(size))) {
    throw ImageError(std::string(what) + ": cannot read '" + path.string() + "'");
  }
  return bytes;
}

void write_file_bytes(const std::filesystem::path& path, std::span<const uint8_t> bytes,
                      std::string_view what) {
  std::ofstream out(path, std::ios::binary | std::ios::trunc);
  if (!out) {
    throw ImageError(std::string(what) + ": cannot create '" + path.string() +
                     "': " + std::strerror(errno));
  }
  out.write(reinterpret_cast<const char*>(bytes.data()), static_cast<std::streamsize>(bytes.size()));
  out.flush();
  if (!out) throw ImageError(std::string(what) + ": cannot write '" + path.string() + "'");
}

}  // namespace strata::image::detail
