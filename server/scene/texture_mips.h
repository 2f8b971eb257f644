#pragma once
// Mip chains for decoded textures, built on the host. Level l + 1 halves level l (rounding down,
// at least 1 texel); each of its texels is the mean of the level-l texels its footprint covers
// (2 x 2, or 3 wide / high at the odd last row and column, so every texel counts once). sRGB
// images are averaged in linear space (decode, mean, re-encode with rounding), so a level keeps
// the brightness of the one above; alpha and linear images are averaged as stored. Normal maps
// are averaged like any linear image (the lookup renormalises).
#include <cstdint>
#include <string>

#include "image/texture_decode.h"
#include "scene/scene.h"

namespace strata::scene {

// Texels of the whole chain of a width x height image.
uint64_t mip_chain_texels(uint32_t width, uint32_t height);

// Appends `image` and its mip chain to `set`; returns the index of the new TextureImage.
uint32_t add_texture_image(TextureSet& set, const image::Rgba8Image& image, ColorSpace color_space,
                           const std::string& name);

// Appends `image` (add_texture_image) and a texture of it with `sampler` to `set`; returns the
// texture's index (a TextureRef::texture).
int32_t add_texture(TextureSet& set, const image::Rgba8Image& image, ColorSpace color_space, const std::string& name,
                    const Sampler& sampler = {});

// The sRGB transfer functions used for the chain (IEC 61966-2-1).
float srgb_to_linear(uint8_t value);
uint8_t linear_to_srgb(float value);

}  // namespace strata::scene
