#pragma once
// What a scene holds that its rendered image does not show: the features its file held that the
// scene model leaves out (Scene::ignored_features), then what the model keeps that the renderer
// does not yet draw. `stratad render` prints the list and CreateSession reports it in
// SceneAnalysis.ignored, so nothing a file asks for is dropped without a word.
#include <string>
#include <vector>

#include "scene/scene.h"

namespace strata::scene {

std::vector<std::string> unrendered_features(const Scene& scene);

}  // namespace strata::scene
