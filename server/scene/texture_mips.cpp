#include "scene/texture_mips.h"

#include <algorithm>
#include <array>
#include <cmath>

namespace strata::scene {
namespace {

const std::array<float, 256>& srgb_table() {
  static const std::array<float, 256> table = [] {
    std::array<float, 256> t{};
    for (int i = 0; i < 256; ++i) {
      const double c = i / 255.0;
      t[size_t(i)] = float(c <= 0.04045 ? c / 12.92 : std::pow((c + 0.055) / 1.055, 2.4));
    }
    return t;
  }();
  return table;
}

uint8_t to_unorm8(float value) {
  return static_cast<uint8_t>(std::lround(std::clamp(value, 0.0f, 1.0f) * 255.0f));
}

// Level `src` (w x h) halved into `dst` (dw x dh).
void downsample(const uint32_t* src, uint32_t w, uint32_t h, uint32_t* dst, uint32_t dw, uint32_t dh,
                ColorSpace color_space) {
  for (uint32_t y = 0; y < dh; ++y) {
    const uint32_t y0 = uint32_t(uint64_t(y) * h / dh), y1 = uint32_t(uint64_t(y + 1) * h / dh);
    for (uint32_t x = 0; x < dw; ++x) {
      const uint32_t x0 = uint32_t(uint64_t(x) * w / dw), x1 = uint32_t(uint64_t(x + 1) * w / dw);
      float sum[4] = {0, 0, 0, 0};
      for (uint32_t sy = y0; sy < y1; ++sy) {
        for (uint32_t sx = x0; sx < x1; ++sx) {
          const uint32_t t = src[size_t(sy) * w + sx];
          for (int c = 0; c < 4; ++c) {
            const uint8_t v = uint8_t(t >> (8 * c));
            sum[c] += c < 3 && color_space == ColorSpace::kSrgb ? srgb_to_linear(v) : v / 255.0f;
          }
        }
      }
      const float n = float((x1 - x0) * (y1 - y0));
      uint32_t out = 0;
      for (int c = 0; c < 4; ++c) {
        const float mean = sum[c] / n;
        const uint8_t v = c < 3 && color_space == ColorSpace::kSrgb ? linear_to_srgb(mean) : to_unorm8(mean);
        out |= uint32_t(v) << (8 * c);
      }
      dst[size_t(y) * dw + x] = out;
    }
  }
}

}  // namespace

float srgb_to_linear(uint8_t value) { return srgb_table()[value]; }

uint8_t linear_to_srgb(float value) {
  const double c = std::clamp(double(value), 0.0, 1.0);
  return to_unorm8(float(c <= 0.0031308 ? c * 12.92 : 1.055 * std::pow(c, 1.0 / 2.4) - 0.055));
}

uint64_t mip_chain_texels(uint32_t width, uint32_t height) {
  uint64_t total = 0;
  for (;;) {
    total += uint64_t(width) * height;
    if (width == 1 && height == 1) return total;
    width = std::max(1u, width / 2);
    height = std::max(1u, height / 2);
  }
}

uint32_t add_texture_image(TextureSet& set, const image::Rgba8Image& image, ColorSpace color_space,
                           const std::string& name) {
  TextureImage out;
  out.name = name;
  out.color_space = color_space;
  out.first_level = uint32_t(set.levels.size());
  uint32_t w = image.width, h = image.height;
  size_t offset = set.texels.size();
  set.texels.resize(offset + mip_chain_texels(w, h));
  std::copy(image.texels.begin(), image.texels.end(), set.texels.begin() + std::ptrdiff_t(offset));
  for (;;) {
    set.levels.push_back({w, h, uint32_t(offset)});
    ++out.level_count;
    if (w == 1 && h == 1) break;
    const uint32_t dw = std::max(1u, w / 2), dh = std::max(1u, h / 2);
    const size_t next = offset + size_t(w) * h;
    downsample(&set.texels[offset], w, h, &set.texels[next], dw, dh, color_space);
    offset = next;
    w = dw;
    h = dh;
  }
  set.images.push_back(std::move(out));
  return uint32_t(set.images.size() - 1);
}

int32_t add_texture(TextureSet& set, const image::Rgba8Image& image, ColorSpace color_space, const std::string& name,
                    const Sampler& sampler) {
  Texture t;
  t.image = add_texture_image(set, image, color_space, name);
  t.sampler = sampler;
  set.textures.push_back(t);
  return int32_t(set.textures.size() - 1);
}

}  // namespace strata::scene
