#pragma once
// The viewer's overlays: images drawn over a frame in the page. One today, the domain map of a
// method with pixel layers (render/restir/domain_map.h): per pixel, its active domains, whether its
// front layer was disoccluded and whether a splat from a previous deep domain covered it, as a PNG
// (red 32 x the active domains, green disoccluded, blue covered) with a summary of the same.
#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "render/restir/domain_map.h"

namespace strata::http {

struct Overlay {
  std::vector<uint8_t> png;
  nlohmann::json header;  // kind, bytes, width, height, layers and the map's summary
};

// The summary of a domain map: mean active domains per pixel, the share of pixels whose front layer
// was disoccluded, and the share of those that a splat covered (ML Table 1's statistics).
nlohmann::json domain_map_summary(const render::DomainMap& map);

// The methods whose frames have a domain map (pixel layers): the page offers the overlay for them.
std::vector<std::string> domain_map_methods();

// The frame's domain map as an overlay; none when the frame carries no map.
std::optional<Overlay> domain_map_overlay(const std::optional<render::DomainMap>& map);

}  // namespace strata::http
