#pragma once
// What a scene contains, as far as the methods' choices depend on it (Session.analysis).
#include "scene/scene.h"
#include "strata/v1/render.pb.h"

namespace strata::service {

::strata::v1::SceneAnalysis analyze_scene(const scene::Scene& scene);

}  // namespace strata::service
