#include "scene/unrendered.h"

namespace strata::scene {

std::vector<std::string> unrendered_features(const Scene& scene) {
  return scene.ignored_features;
}

}  // namespace strata::scene
