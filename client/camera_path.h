#pragma once
// Camera/transform/LoD scripts for `strata stream --camera-path FILE.json`:
//   {"frames": [FrameInput, FrameInput, ...]}
// each entry a strata.v1.FrameInput in the proto3 JSON mapping (field names in snake_case or
// lowerCamelCase), one entry per frame, e.g.
//   {"animation_frame": 3, "lod_changes": [{"instance_id": 1, "level": 2}]}
//   {"camera": {"position": {"x": 0, "y": 1, "z": 5}, "orientation": {"w": 1}, "vertical_fov": 0.8},
//    "transforms": [{"instance_id": 2, "translation": {"x": 1}, "rotation": {"w": 1},
//                    "scale": {"x": 1, "y": 1, "z": 1}}],
//    "options": {"spp": 2}, "resolution": {"width": 64, "height": 48}}
// `session` and `sequence` are filled in by strata.
#include <filesystem>
#include <vector>

#include "strata/v1/render.pb.h"

namespace strata::client {

// Throws std::runtime_error naming the file, the entry and what is wrong.
std::vector<strata::v1::FrameInput> load_camera_path(const std::filesystem::path& file);

}  // namespace strata::client
