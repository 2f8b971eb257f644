#pragma once
// How many pixel layers restir-multilayer keeps when the session asks for `layers auto` (ML Sec. 6:
// "we set the maximum layer count based on (visible) scene depth complexity, which ranges from 2 to
// 5"): measured once, on the scene's first frame, from pixel-centre rays walked through their
// surfaces (front faces counted as restir/layer_data.h defines layers).
#include <cstdint>
#include <string>

#include "gpu/context.h"
#include "scene/scene.h"

namespace strata::render {

struct LayerCount {
  uint32_t layers = 1;  // k: the front layer and the deep layers that enough pixels have
  std::string reason;   // the measured figures, for the session's `layers` decision
};

// A deep layer is kept while at least this share of the surface-hitting rays reach it.
inline constexpr double k_layer_share = 0.10;

// Walks a grid of pixel-centre rays (at most 64 x 64, in the image's aspect) of `frame` through the
// scene (at most LAYERS_MAX layers) and keeps 1 + the deepest layer that k_layer_share of them reach.
LayerCount measure_layers(const gpu::Context& ctx, const scene::Scene& scene, const scene::FrameState& frame, uint32_t width,
                          uint32_t height);

}  // namespace strata::render
