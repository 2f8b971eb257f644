#pragma once
// Internal to the glTF loader: from bytes to a tinygltf::Model, safely. Checks the .glb
// container and the JSON nesting before tinygltf sees them, confines external URIs to the
// directory of the file being loaded (none for in-memory data), and counts every byte read
// against LoadLimits::max_file_bytes.
#include <cstdint>
#include <filesystem>
#include <optional>
#include <span>
#include <string>
#include <vector>

#include <tiny_gltf.h>

#include "scene/scene_io.h"

namespace strata::scene::gltf {

// The whole of a regular file, or SceneError (unreadable, not a regular file, over the limit).
std::vector<uint8_t> read_file(const std::filesystem::path& path, const LoadLimits& limits);

// Parses .glb or .gltf bytes. `directory`: where external URIs may point (nullopt: nowhere).
// `budget`: bytes external files may still add.
tinygltf::Model parse_model(std::span<const uint8_t> bytes, const std::string& label,
                            const std::optional<std::filesystem::path>& directory, uint64_t budget);

}  // namespace strata::scene::gltf
