// EXR encode/decode through OpenEXR's general scanline API, so that AOVs can ride along as extra
// FLOAT channels next to the HALF colour channels.
#include <algorithm>
#include <array>
#include <climits>
#include <exception>
#include <set>
#include <string>

#include <Imath/half.h>
#include <OpenEXR/ImfChannelList.h>
#include <OpenEXR/ImfFrameBuffer.h>
#include <OpenEXR/ImfHeader.h>
#include <OpenEXR/ImfInputFile.h>
#include <OpenEXR/ImfOutputFile.h>

#include "image/exr_bounds.h"
#include "image/exr_memory_stream.h"
#include "image/image.h"
#include "image/image_util.h"

namespace strata::image {
namespace {

constexpr std::array<const char*, 4> kRgba = {"R", "G", "B", "A"};
// Decoding refuses data windows above this (a corrupt header must not trigger a huge allocation).
constexpr int64_t kMaxPixels = int64_t(1) << 28;

bool is_rgba_name(const std::string& name) {
  return name == "R" || name == "G" || name == "B" || name == "A";
}

void check_extra(const Image& img, std::span<const Channel> extra) {
  std::set<std::string> seen;
  const size_t pixels = size_t(img.width) * img.height;
  for (const Channel& c : extra) {
    if (c.name.empty() || is_rgba_name(c.name) || !seen.insert(c.name).second) {
      throw ImageError("encode_exr: extra channel name '" + c.name +
                       "' is empty, duplicated or one of R, G, B, A");
    }
    if (c.values.size() != pixels) {
      throw ImageError("encode_exr: extra channel '" + c.name + "' holds " +
                       std::to_string(c.values.size()) + " values, the image has " +
                       std::to_string(pixels) + " pixels");
    }
  }
}

// Everything OpenEXR throws (Iex::BaseExc derives from std::exception) and our own checks inside
// `f` become an ImageError that says which operation on which file failed.
template <typename F>
auto convert_errors(const std::string& context, F&& f) {
  try {
    return f();
  } catch (const std::exception& e) {
    throw ImageError(context + ": " + e.what());
  }
}

// `max_pixels`: kMaxPixels, or less for bytes in memory (detail::max_exr_pixels_for).
Image read_stream(Imf::IStream& stream, std::vector<Channel>* extra, int64_t max_pixels = kMaxPixels) {
  Imf::InputFile file(stream);
  const Imath::Box2i dw = file.header().dataWindow();
  const int64_t w = int64_t(dw.max.x) - dw.min.x + 1;
  const int64_t h = int64_t(dw.max.y) - dw.min.y + 1;
  if (w <= 0 || h <= 0 || w > max_pixels / h) {
    throw ImageError("data window of " + std::to_string(w) + "x" + std::to_string(h) +
                     " pixels is empty or too large (at most " + std::to_string(max_pixels) + " pixels here)");
  }
  const Imf::ChannelList& channels = file.header().channels();
  if (!channels.findChannel("R") && !channels.findChannel("G") && !channels.findChannel("B")) {
    throw ImageError("no R, G or B channel");
  }
  Image img{static_cast<uint32_t>(w), static_cast<uint32_t>(h), {}};
  img.rgba.resize(4 * size_t(w) * size_t(h));
  Imf::FrameBuffer fb;
  for (size_t c = 0; c < kRgba.size(); ++c) {
    // OpenEXR converts HALF (or UINT) samples to FLOAT; a channel the file lacks reads as the
    // fill value, which gives opaque alpha for RGB-only files.
    const double fill = c == 3 ? 1.0 : 0.0;
    fb.insert(kRgba[c], Imf::Slice::Make(Imf::FLOAT, img.rgba.data() + c, dw, 4 * sizeof(float), 0,
                                          1, 1, fill));
  }
  if (extra) {
    for (auto it = channels.begin(); it != channels.end(); ++it) {
      if (is_rgba_name(it.name())) continue;
      extra->push_back({it.name(), std::vector<float>(size_t(w) * size_t(h))});
    }
    for (Channel& c : *extra) {
      fb.insert(c.name, Imf::Slice::Make(Imf::FLOAT, c.values.data(), dw, sizeof(float)));
    }
  }
  file.setFrameBuffer(fb);
  file.readPixels(dw.min.y, dw.max.y);
  return img;
}

Image decode_bytes(std::span<const uint8_t> bytes, const std::string& name,
                   std::vector<Channel>* extra) {
  return convert_errors("cannot decode EXR '" + name + "'", [&] {
    detail::check_exr_header_bounds(bytes);
    detail::MemoryIStream stream(bytes, name.c_str());
    return read_stream(stream, extra, std::min(kMaxPixels, detail::max_exr_pixels_for(bytes.size())));
  });
}

}  // namespace

std::vector<uint8_t> encode_exr(const Image& img, std::span<const Channel> extra) {
  detail::check_image(img, "encode_exr");
  if (img.width > INT_MAX || img.height > INT_MAX) {
    throw ImageError("encode_exr: image of " + std::to_string(img.width) + "x" +
                     std::to_string(img.height) + " exceeds the EXR size limit");
  }
  check_extra(img, extra);
  const int w = static_cast<int>(img.width);
  const int h = static_cast<int>(img.height);
  std::vector<Imath::half> halves(img.rgba.begin(), img.rgba.end());
  return convert_errors("encode_exr: OpenEXR failed", [&] {
    Imf::Header header(w, h);
    header.compression() = Imf::ZIP_COMPRESSION;
    Imf::FrameBuffer fb;
    const size_t x_stride = 4 * sizeof(Imath::half);
    for (size_t c = 0; c < kRgba.size(); ++c) {
      header.channels().insert(kRgba[c], Imf::Channel(Imf::HALF));
      fb.insert(kRgba[c], Imf::Slice(Imf::HALF, reinterpret_cast<char*>(halves.data() + c), x_stride,
                                     x_stride * img.width));
    }
    for (const Channel& c : extra) {
      header.channels().insert(c.name, Imf::Channel(Imf::FLOAT));
      // Slice wants a mutable pointer for both directions; OutputFile only reads through it.
      char* base = reinterpret_cast<char*>(const_cast<float*>(c.values.data()));
      fb.insert(c.name, Imf::Slice(Imf::FLOAT, base, sizeof(float), sizeof(float) * img.width));
    }
    detail::MemoryOStream stream;
    {
      // The line offset table is written when the file object is destroyed.
      Imf::OutputFile file(stream, header);
      file.setFrameBuffer(fb);
      file.writePixels(h);
    }
    return stream.take();
  });
}

void write_exr(const std::filesystem::path& path, const Image& img, std::span<const Channel> extra) {
  detail::write_file_bytes(path, encode_exr(img, extra), "write_exr");
}

Image read_exr(const std::filesystem::path& path) {
  const std::vector<uint8_t> bytes = detail::read_file_bytes(path, "read_exr");
  return decode_bytes(bytes, path.string(), nullptr);
}

Image decode_exr(std::span<const uint8_t> bytes) { return decode_bytes(bytes, "<memory>", nullptr); }

std::vector<Channel> decode_exr_extra_channels(std::span<const uint8_t> bytes) {
  std::vector<Channel> extra;
  decode_bytes(bytes, "<memory>", &extra);
  return extra;
}

}  // namespace strata::image
