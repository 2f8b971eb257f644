#include "render/restir/domain_map.h"

#include <algorithm>

#include "restir/domain.h"
#include "restir/layer_data.h"

namespace strata::render {

DomainMap read_domain_map(const gpu::Buffer& ranges, uint32_t width, uint32_t height, uint32_t layers) {
  DomainMap map{.width = width, .height = height, .layers = layers, .pixels = {}};
  const size_t pixels = size_t(width) * height;
  const auto r = ranges.download_as<gpu::GpuDomainRange>(pixels * layers);
  map.pixels.resize(pixels);
  for (uint32_t y = 0; y < height; ++y)
    for (uint32_t x = 0; x < width; ++x) {
      uint8_t v = 0;
      for (uint32_t layer = 0; layer < layers; ++layer)
        if (r[gpu::domain_index({x, y}, layer, width, height)].flags & gpu::DOMAIN_ACTIVE) ++v;
      const uint32_t front = r[gpu::domain_index({x, y}, 0, width, height)].flags;
      if (front & gpu::DOMAIN_DISOCCLUDED) v |= DomainMap::k_disoccluded;
      if (front & gpu::DOMAIN_COVERED) v |= DomainMap::k_covered;
      map.pixels[size_t(y) * width + x] = v;
    }
  return map;
}

std::vector<uint8_t> domain_map_rgb(const DomainMap& map) {
  std::vector<uint8_t> rgb(map.pixels.size() * 3);
  for (size_t i = 0; i < map.pixels.size(); ++i) {
    const uint8_t v = map.pixels[i];
    rgb[3 * i + 0] = uint8_t(std::min(255u, 32u * (v & DomainMap::k_active_mask)));
    rgb[3 * i + 1] = (v & DomainMap::k_disoccluded) ? 255 : 0;
    rgb[3 * i + 2] = (v & DomainMap::k_covered) ? 255 : 0;
  }
  return rgb;
}

}  // namespace strata::render
