#include "scene/unrendered.h"

#include "scene/gltf_extensions.h"

namespace strata::scene {

std::vector<std::string> unrendered_features(const Scene& scene) {
  std::vector<std::string> out = scene.ignored_features;
  // Textures are sampled and MASK is alpha-tested (render/scene_textures.h); BLEND is approximated.
  size_t blended = 0;
  for (const Material& m : scene.materials) blended += m.alpha_mode == AlphaMode::kBlend ? 1 : 0;
  if (blended > 0)
    out.push_back("alphaMode BLEND on " + gltf::count_of(blended, "material") + " (rendered as MASK at alpha cutoff 0.5)");
  return out;
}

}  // namespace strata::scene
