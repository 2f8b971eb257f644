// Texture images as glTF files bring them: any bytes must give a decoded PNG or JPEG with its mip
// chain, or an ImageError naming the problem (unsupported type, bad header, undecodable data,
// a side over the limit).
#include <span>

#include "fuzz_support.h"
#include "image/texture_decode.h"
#include "scene/texture_mips.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  strata::fuzz::expect_clean("texture", [&] {
    const std::span<const uint8_t> bytes(data, size);
    // A small limit keeps each input fast; it is the same check with a smaller number.
    const strata::image::Rgba8Image decoded = strata::image::decode_rgba8(bytes, 1024);
    strata::scene::TextureSet set;
    (void)strata::scene::add_texture_image(set, decoded, strata::scene::ColorSpace::kSrgb, "fuzz");
  });
  return 0;
}
