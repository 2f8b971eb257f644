#pragma once
// What `strata stream` leaves on disk: frame_NNNN.exr and frame_NNNN.png per frame, and the
// messages the server returned as JSON (images replaced by the files they went to).
#include <filesystem>
#include <string>

#include <google/protobuf/message.h>
#include <nlohmann/json.hpp>

#include "image/image.h"
#include "strata/v1/render.pb.h"

namespace strata::client {

// The proto3 JSON mapping with field names as in the .proto and every field present.
nlohmann::json message_to_json(const google::protobuf::Message& m);

std::string frame_file_stem(uint64_t frame_index);

// Writes frame_NNNN.exr and .png: the server's EXR_HALF and PNG_PREVIEW bytes as they came, and
// whichever of the two the server did not send made here from the other images (PNG previews at
// `exposure` stops). Returns the Frame as JSON with "images" listing encoding, size and file.
nlohmann::json write_frame(const strata::v1::Frame& frame, const std::filesystem::path& dir, float exposure);

}  // namespace strata::client
