#pragma once
// Textures generated in code for the textured built-in scenes (courtyard, night-street, atrium):
// small (64 x 64 texels or fewer), deterministic, repeating and trilinear.
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <string>

#include "scene/scene.h"
#include "scene/texture_mips.h"

namespace strata::scene::builtin {

// An RGBA8 texel word (R | G << 8 | B << 16 | A << 24) from channels in [0, 1] (clamped).
inline uint32_t rgba(float r, float g, float b, float a = 1.0f) {
  auto byte = [](float v) { return uint32_t(std::lround(std::clamp(v, 0.0f, 1.0f) * 255.0f)); };
  return byte(r) | byte(g) << 8 | byte(b) << 16 | byte(a) << 24;
}

// A texture of a generated image (texel(x, y) -> RGBA8 word), trilinear and repeating.
template <typename Texel>
int32_t add_generated(Scene& s, const std::string& name, uint32_t w, uint32_t h, ColorSpace space, Texel texel) {
  image::Rgba8Image img{w, h, {}};
  for (uint32_t y = 0; y < h; ++y)
    for (uint32_t x = 0; x < w; ++x) img.texels.push_back(texel(x, y));
  return add_texture(s.textures, img, space, name);
}

// A leaf card (32 x 32, sRGB): two leaves (ellipses) on a transparent ground, their veins darker;
// for a MASK material at cutoff 0.5.
int32_t leaf_texture(Scene& s);

// Value noise in [0, 1] on a lattice of `cell` texels that repeats every `period` texels (bilinear
// between hashed lattice values), for weathered surfaces that tile without seams.
float tiled_noise(uint32_t x, uint32_t y, uint32_t cell, uint32_t period, uint32_t seed);

}  // namespace strata::scene::builtin
