// The client's EXR decoding (strata eval decodes frames and references it receives; frames.json
// tools read frame_NNNN.exr): any bytes must give an image or an ImageError.
#include <span>

#include "fuzz_support.h"
#include "image/image.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  strata::fuzz::expect_clean("exr", [&] {
    const std::span<const uint8_t> bytes(data, size);
    (void)strata::image::decode_exr(bytes);
    (void)strata::image::decode_exr_extra_channels(bytes);
  });
  return 0;
}
