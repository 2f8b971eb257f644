#pragma once
// Checks of EXR bytes made before OpenEXR sees them, against what a small file could otherwise
// make the decoder allocate (found by tests/fuzz's EXR target): OpenEXR allocates an attribute's
// declared size before reading it, and the whole data window before reading pixels.
#include <cstdint>
#include <span>

namespace strata::image::detail {

// Walks the header attributes as OpenEXR's C++ reader does and throws ImageError when one
// declares more bytes than the file has left, a fixed-size or channel-list attribute declares a
// size other than the one it holds, the header is cut short, or its data window (times its
// channels, and at least 32 lines) is more than max_exr_pixels_for(bytes) samples. Leaves
// everything else to OpenEXR.
void check_exr_header_bounds(std::span<const uint8_t> bytes);

// The most pixels `file_bytes` of EXR can honestly hold: zlib (ZIP) compresses at most about
// 1032:1, and a pixel has at least one 2-byte HALF sample, so 1024 pixels per byte is generous to
// any real file and stops a few hundred bytes from claiming gigabytes.
int64_t max_exr_pixels_for(uint64_t file_bytes);

}  // namespace strata::image::detail
