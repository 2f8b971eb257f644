#pragma once
// `light_sampler auto`, the default (docs/ARCHITECTURE.md, "Light sampling"): the light tree where
// the scene has many bounded lights, the alias table by power where it has a few. Measured with pt
// at 1 spp (docs/BENCHMARKS.md, "Many lights"): with 822 bounded lights (night-street) the tree has
// 0.29x power's error at equal time; with 2-4 (every other built-in scene) it has nothing to choose
// between, costs 1-9% more per frame, and is 0.85-1.10x power's error at equal time.
#include <cstdint>

#include "render/restir/restir_options.h"
#include "scene/scene.h"

namespace strata::render {

// Where `auto` takes the tree: at least this many bounded lights.
inline constexpr uint64_t k_auto_light_tree_min_lights = 16;

// The lights the tree holds: emissive triangles (each instance at its current LoD level) and point
// and spot lights. Directional lights and the environment are chosen beside it.
uint64_t bounded_lights(const scene::Scene& scene);

// The sampler `requested` stands for with `bounded` bounded lights: power or tree.
LightSampler light_sampler_in_use(LightSampler requested, uint64_t bounded);

}  // namespace strata::render
