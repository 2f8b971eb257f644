#include "scene/unrendered.h"

#include "scene/gltf_extensions.h"

namespace strata::scene {

std::vector<std::string> unrendered_features(const Scene& scene) {
  std::vector<std::string> out = scene.ignored_features;
  // Textures and alpha modes are in the scene model (Scene::textures, Material); the renderer
  // does not sample them yet.
  struct Slot {
    const char* name;
    TextureRef Material::*ref;
  };
  constexpr Slot kSlots[] = {{"baseColorTexture", &Material::base_color_texture},
                             {"metallicRoughnessTexture", &Material::metallic_roughness_texture},
                             {"normalTexture", &Material::normal_texture},
                             {"emissiveTexture", &Material::emissive_texture}};
  for (const Slot& slot : kSlots) {
    size_t count = 0;
    for (const Material& m : scene.materials) count += (m.*slot.ref).texture >= 0 ? 1 : 0;
    if (count > 0) {
      out.push_back(std::string(slot.name) + " on " + gltf::count_of(count, "material") +
                    " (textures are decoded but not yet sampled)");
    }
  }
  size_t masked = 0, blended = 0;
  for (const Material& m : scene.materials) {
    masked += m.alpha_mode == AlphaMode::kMask ? 1 : 0;
    blended += m.alpha_mode == AlphaMode::kBlend ? 1 : 0;
  }
  if (masked > 0)
    out.push_back("alphaMode MASK on " + gltf::count_of(masked, "material") + " (rendered opaque: not yet alpha-tested)");
  if (blended > 0)
    out.push_back("alphaMode BLEND on " + gltf::count_of(blended, "material") + " (rendered opaque)");
  if (scene.environment.map) {
    out.push_back("environment map '" + scene.environment.map->name +
                  "' (loaded, not yet rendered: escaping rays see the constant environment colour)");
  }
  return out;
}

}  // namespace strata::scene
