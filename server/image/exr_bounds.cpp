#include "image/exr_bounds.h"

#include <algorithm>
#include <map>
#include <string>

#include "image/image.h"

namespace strata::image::detail {
namespace {

constexpr uint32_t k_magic = 20000630;
constexpr uint32_t k_multipart_flag = 0x1000;  // version field bit 12
constexpr size_t k_max_name = 255;             // long names (version bit 10); short ones are 31

// The sizes OpenEXR's C++ reader consumes for its fixed-size attribute types whatever the header
// declares. A declared size that differs would make its reading and this walk part ways, so it is
// refused. Other types (string, stringvector, opaque ones) are read for their declared size.
const std::map<std::string, uint32_t>& fixed_sizes() {
  static const std::map<std::string, uint32_t> sizes = {
      {"box2i", 16}, {"box2f", 16}, {"chromaticities", 32}, {"compression", 1}, {"double", 8}, {"envmap", 1},
      {"float", 4}, {"int", 4}, {"keycode", 28}, {"lineOrder", 1}, {"m33f", 36}, {"m44f", 64}, {"m33d", 72},
      {"m44d", 128}, {"rational", 8}, {"tiledesc", 9}, {"timecode", 8}, {"v2i", 8}, {"v2f", 8}, {"v3i", 12},
      {"v3f", 12}, {"v2d", 16}, {"v3d", 24}, {"deepImageState", 1}};
  return sizes;
}

struct Reader {
  std::span<const uint8_t> bytes;
  size_t at = 0;
  [[noreturn]] void fail(const std::string& what) const {
    throw ImageError("EXR header: " + what + " at byte " + std::to_string(at) + " of " + std::to_string(bytes.size()));
  }
  uint32_t u32() {
    if (bytes.size() - at < 4) fail("cut short");
    const uint32_t v = uint32_t(bytes[at]) | uint32_t(bytes[at + 1]) << 8 | uint32_t(bytes[at + 2]) << 16 | uint32_t(bytes[at + 3]) << 24;
    at += 4;
    return v;
  }
  // A NUL-terminated string ("" ends a header or a channel list).
  std::string name() {
    for (size_t i = at; i < bytes.size() && i - at <= k_max_name; ++i)
      if (bytes[i] == 0) {
        std::string s(reinterpret_cast<const char*>(bytes.data() + at), i - at);
        at = i + 1;
        return s;
      }
    fail("a name without its terminating NUL within " + std::to_string(k_max_name) + " bytes");
  }
};

// The bytes a channel list takes as OpenEXR reads it: entries of a name and 16 bytes, then "".
size_t channel_list_size(Reader r) {
  const size_t start = r.at;
  while (!r.name().empty()) {
    if (r.bytes.size() - r.at < 16) r.fail("a channel list cut short");
    r.at += 16;
  }
  return r.at - start;
}

size_t count_channels(Reader r) {
  size_t n = 0;
  while (!r.name().empty()) {
    r.at += 16;
    ++n;
  }
  return n;
}

}  // namespace

void check_exr_header_bounds(std::span<const uint8_t> bytes) {
  const int64_t max_samples = max_exr_pixels_for(bytes.size());
  Reader r{bytes};
  if (r.u32() != k_magic) return;  // not EXR: OpenEXR says so in its own words
  const bool multipart = (r.u32() & k_multipart_flag) != 0;
  for (;;) {
    size_t attributes = 0, channels = 0;
    int64_t width = 0, height = 0;
    for (std::string name = r.name(); !name.empty(); name = r.name(), ++attributes) {
      const std::string type = r.name();
      if (type.empty()) r.fail("attribute '" + name + "' without a type");
      const uint32_t size = r.u32();
      if (size > bytes.size() - r.at)
        r.fail("attribute '" + name + "' declares " + std::to_string(size) + " bytes, more than the " +
               std::to_string(bytes.size() - r.at) + " left in the file");
      const auto fixed = fixed_sizes().find(type);
      const size_t natural = type == "chlist" ? channel_list_size(r) : fixed != fixed_sizes().end() ? fixed->second : size;
      if (natural != size)
        r.fail("attribute '" + name + "' of type " + type + " declares " + std::to_string(size) + " bytes but holds " +
               std::to_string(natural));
      if (type == "chlist") channels += count_channels(r);
      if (name == "dataWindow" && type == "box2i") {
        Reader box = r;
        const auto x0 = int32_t(box.u32()), y0 = int32_t(box.u32()), x1 = int32_t(box.u32()), y1 = int32_t(box.u32());
        width = int64_t(x1) - x0 + 1;
        height = int64_t(y1) - y0 + 1;
      }
      r.at += size;
    }
    if (attributes == 0) return;  // the empty header that ends a multi-part file's list
    // OpenEXR sizes its line buffers from the data window (at least 32 lines: PIZ's chunk) and
    // the channels before it reads a pixel, so a lying window costs memory at construction.
    if (width <= 0 || height <= 0 || width > max_samples / std::max<int64_t>(height, 32) / std::max<int64_t>(int64_t(channels), 1))
      throw ImageError("EXR header: a data window of " + std::to_string(width) + "x" + std::to_string(height) + " with " +
                       std::to_string(channels) + " channels is empty or more than " + std::to_string(bytes.size()) +
                       " bytes of EXR can hold");
    // A multi-part file lists headers until an empty one; a single-part file has one.
    if (!multipart) return;
  }
}

int64_t max_exr_pixels_for(uint64_t file_bytes) { return int64_t(file_bytes) * 1024 + 4096; }

}  // namespace strata::image::detail
