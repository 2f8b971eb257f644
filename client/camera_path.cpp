#include "camera_path.h"

#include <fstream>
#include <sstream>
#include <stdexcept>

#include <google/protobuf/util/json_util.h>
#include <nlohmann/json.hpp>

namespace strata::client {

std::vector<strata::v1::FrameInput> load_camera_path(const std::filesystem::path& file) {
  const std::string name = file.string();
  std::ifstream in(file);
  if (!in) throw std::runtime_error(name + ": cannot read the camera path");
  nlohmann::json doc;
  try {
    doc = nlohmann::json::parse(in);
  } catch (const nlohmann::json::exception& e) {
    throw std::runtime_error(name + ": not valid JSON: " + e.what());
  }
  if (!doc.is_object() || !doc.contains("frames") || !doc["frames"].is_array() || doc["frames"].empty())
    throw std::runtime_error(name + ": expected {\"frames\": [FrameInput, ...]} with at least one frame");
  std::vector<strata::v1::FrameInput> frames;
  google::protobuf::util::JsonParseOptions options;
  options.ignore_unknown_fields = false;
  for (size_t i = 0; i < doc["frames"].size(); ++i) {
    strata::v1::FrameInput input;
    const auto status = google::protobuf::util::JsonStringToMessage(doc["frames"][i].dump(), &input, options);
    if (!status.ok())
      throw std::runtime_error(name + ": frames[" + std::to_string(i) + "]: " + std::string(status.message()));
    input.clear_session();
    input.clear_sequence();
    frames.push_back(std::move(input));
  }
  return frames;
}

}  // namespace strata::client
