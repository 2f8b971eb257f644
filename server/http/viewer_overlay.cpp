#include "http/viewer_overlay.h"

#include <algorithm>

#include "image/image.h"
#include "render/method_table.h"

namespace strata::http {

std::vector<std::string> domain_map_methods() {
  std::vector<std::string> out;
  for (const auto& m : render::method_table())
    if (m.layers) out.push_back(m.name);
  return out;
}

nlohmann::json domain_map_summary(const render::DomainMap& map) {
  uint64_t active = 0, disoccluded = 0, covered = 0;
  for (const uint8_t v : map.pixels) {
    active += v & render::DomainMap::k_active_mask;
    if (v & render::DomainMap::k_disoccluded) {
      ++disoccluded;
      if (v & render::DomainMap::k_covered) ++covered;
    }
  }
  const double pixels = double(std::max<size_t>(1, map.pixels.size()));
  return {{"active_domains_mean", double(active) / pixels},
          {"disoccluded_share", double(disoccluded) / pixels},
          {"covered_share_of_disoccluded", disoccluded ? double(covered) / double(disoccluded) : 0.0}};
}

std::optional<Overlay> domain_map_overlay(const std::optional<render::DomainMap>& map) {
  if (!map || map->pixels.empty()) return std::nullopt;
  Overlay o;
  o.png = image::encode_png_rgb8(render::domain_map_rgb(*map), map->width, map->height);
  o.header = {{"kind", "domain_map"},
              {"bytes", o.png.size()},
              {"width", map->width},
              {"height", map->height},
              {"layers", map->layers},
              {"summary", domain_map_summary(*map)}};
  return o;
}

}  // namespace strata::http
