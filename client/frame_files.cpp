#include "frame_files.h"

#include <cstdio>
#include <cstring>
#include <fstream>
#include <stdexcept>

#include <glm/gtc/packing.hpp>
#include <google/protobuf/util/json_util.h>

namespace strata::client {
namespace {

namespace fs = std::filesystem;
using strata::v1::Image;

void write_bytes(const fs::path& path, const std::string& bytes) {
  std::ofstream out(path, std::ios::binary);
  out.write(bytes.data(), std::streamsize(bytes.size()));
  if (!out) throw std::runtime_error("cannot write " + path.string());
}

std::string as_string(const std::vector<uint8_t>& v) { return std::string(v.begin(), v.end()); }

const Image* find(const strata::v1::Frame& f, strata::v1::ImageEncoding e) {
  for (const auto& img : f.images())
    if (img.encoding() == e) return &img;
  return nullptr;
}

// The frame's HDR image from whichever HDR encoding it carries.
image::Image hdr_image(const strata::v1::Frame& f) {
  if (const Image* exr = find(f, strata::v1::IMAGE_ENCODING_EXR_HALF)) {
    const auto& d = exr->data();
    return image::decode_exr(std::span<const uint8_t>(reinterpret_cast<const uint8_t*>(d.data()), d.size()));
  }
  if (const Image* raw = find(f, strata::v1::IMAGE_ENCODING_RAW_RGBA16F)) return image::decode_rgba16f(std::span(reinterpret_cast<const uint8_t*>(raw->data().data()), raw->data().size()), raw->width(), raw->height());
  throw std::runtime_error("frame " + std::to_string(f.frame_index()) + " carries no HDR image (EXR_HALF or RAW_RGBA16F)");
}

}  // namespace

nlohmann::json message_to_json(const google::protobuf::Message& m) {
  google::protobuf::util::JsonPrintOptions options;
  options.preserve_proto_field_names = true;
  options.always_print_primitive_fields = true;
  std::string text;
  const auto status = google::protobuf::util::MessageToJsonString(m, &text, options);
  if (!status.ok()) throw std::runtime_error("cannot convert " + m.GetTypeName() + " to JSON: " + std::string(status.message()));
  return nlohmann::json::parse(text);
}


std::string frame_file_stem(uint64_t frame_index) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "frame_%04llu", static_cast<unsigned long long>(frame_index));
  return buf;
}

nlohmann::json write_frame(const strata::v1::Frame& frame, const fs::path& dir, float exposure) {
  const std::string stem = frame_file_stem(frame.frame_index());
  const fs::path exr_path = dir / (stem + ".exr"), png_path = dir / (stem + ".png");
  const Image* exr = find(frame, strata::v1::IMAGE_ENCODING_EXR_HALF);
  const Image* png = find(frame, strata::v1::IMAGE_ENCODING_PNG_PREVIEW);
  if (exr) write_bytes(exr_path, exr->data());
  if (png) write_bytes(png_path, png->data());
  // The domain map (restir-multilayer; the proto's IMAGE_ENCODING_DOMAIN_MAP says its channels).
  const Image* domains = find(frame, strata::v1::IMAGE_ENCODING_DOMAIN_MAP);
  const fs::path domains_path = dir / (stem + "_domains.png");
  if (domains) write_bytes(domains_path, domains->data());
  if (!exr || !png) {
    const image::Image hdr = hdr_image(frame);
    if (!exr) write_bytes(exr_path, as_string(image::encode_exr(hdr)));
    if (!png) write_bytes(png_path, as_string(image::encode_png_preview(hdr, exposure)));
  }

  strata::v1::Frame meta = frame;
  nlohmann::json images = nlohmann::json::array();
  for (const auto& img : frame.images())
    images.push_back({{"encoding", strata::v1::ImageEncoding_Name(img.encoding())},
                      {"width", img.width()},
                      {"height", img.height()},
                      {"bytes", img.data().size()},
                      {"encode_ms", img.encode_ms()}});
  meta.clear_images();
  nlohmann::json j = message_to_json(meta);
  j["images"] = images;
  j["files"] = {{"exr", exr_path.filename().string()}, {"png", png_path.filename().string()}};
  if (domains) j["files"]["domain_map"] = domains_path.filename().string();
  return j;
}

}  // namespace strata::client
