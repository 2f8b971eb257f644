#pragma once
// Frame images in the encodings clients ask for.
#include <cstdint>
#include <vector>

#include "image/image.h"
#include "strata/v1/render.pb.h"

namespace strata::service {

// Encodes `img`; `exposure` (stops) applies to PNG previews. Fills encode_ms with the CPU time spent.
::strata::v1::Image encode_image(const image::Image& img, ::strata::v1::ImageEncoding encoding, float exposure);

}  // namespace strata::service
