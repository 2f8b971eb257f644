#pragma once
// Internal to strata_image: checks and whole-file I/O shared by the EXR and PNG codecs.
#include <cstdint>
#include <filesystem>
#include <span>
#include <string_view>
#include <vector>

#include "image/image.h"

namespace strata::image::detail {

// Throws ImageError (prefixed with `what`) for a zero size or an rgba array of the wrong length.
void check_image(const Image& img, std::string_view what);
std::vector<uint8_t> read_file_bytes(const std::filesystem::path& path, std::string_view what);
void write_file_bytes(const std::filesystem::path& path, std::span<const uint8_t> bytes,
                      std::string_view what);

}  // namespace strata::image::detail
