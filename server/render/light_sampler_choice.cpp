#include "render/light_sampler_choice.h"

#include <algorithm>

namespace strata::render {

uint64_t bounded_lights(const scene::Scene& s) {
  uint64_t n = 0;
  for (const auto& inst : s.instances) {
    const uint32_t mesh = inst.lod_meshes.at(std::min<size_t>(inst.lod, inst.lod_meshes.size() - 1));
    for (const auto& p : s.meshes.at(mesh).primitives) {
      const auto& e = s.materials.at(p.material).emission;
      if (e.r > 0.0f || e.g > 0.0f || e.b > 0.0f) n += p.triangle_count();
    }
  }
  for (const auto& l : s.lights) n += l.type != scene::LightType::kDirectional;
  return n;
}

LightSampler light_sampler_in_use(LightSampler requested, uint64_t bounded) {
  if (requested != LightSampler::automatic) return requested;
  return bounded >= k_auto_light_tree_min_lights ? LightSampler::tree : LightSampler::power;
}

}  // namespace strata::render
