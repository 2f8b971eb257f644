#pragma once
// Frame images in the encodings clients ask for.
#include <cstdint>
#include <vector>

#include "image/image.h"
#include "render/restir/domain_map.h"
#include "strata/v1/render.pb.h"

namespace strata::service {

// Encodes `img`; `exposure` (stops) applies to PNG previews. Fills encode_ms with the CPU time spent.
::strata::v1::Image encode_image(const image::Image& img, ::strata::v1::ImageEncoding encoding, float exposure);

// The DOMAIN_MAP encoding of `map` (the proto's ImageEncoding says the channels).
::strata::v1::Image encode_domain_map(const render::DomainMap& map);

}  // namespace strata::service
