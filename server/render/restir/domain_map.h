#pragma once
// The domain map of restir-multilayer (docs/ARCHITECTURE.md, "Pixel layers"): per pixel of the last
// frame, how many of its domains were active and whether its front layer was disoccluded and
// covered by a splat from a previous deep domain (ML Table 1's statistics, pixel by pixel), read
// back from the domain ranges for the coverage dashboard (the DOMAIN_MAP image encoding).
#include <cstdint>
#include <vector>

#include "gpu/buffer.h"

namespace strata::render {

struct DomainMap {
  static constexpr uint8_t k_active_mask = 0x0F;  // active domains of the pixel, front layer included (0..8)
  static constexpr uint8_t k_disoccluded = 0x10;  // the front layer's hit was hidden from the previous camera
  static constexpr uint8_t k_covered = 0x20;      // ... and a splat from a previous deep domain or the deep backup reached it
  uint32_t width = 0, height = 0, layers = 0;
  std::vector<uint8_t> pixels;  // width x height, top row first
};

// Reads `ranges` (GpuDomainRange per domain, restir/layer_data.h) back and summarizes each pixel.
DomainMap read_domain_map(const gpu::Buffer& ranges, uint32_t width, uint32_t height, uint32_t layers);

// The map as RGB8 pixels for the coverage dashboard (the proto's IMAGE_ENCODING_DOMAIN_MAP): red
// 32 x the active domains, green where the front layer was disoccluded, blue where it was covered.
std::vector<uint8_t> domain_map_rgb(const DomainMap& map);

}  // namespace strata::render
