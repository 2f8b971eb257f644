#pragma once
// What a scene contains, as far as the methods' choices depend on it (Session.analysis).
#include "scene/scene.h"
#include "strata/v1/render.pb.h"

namespace strata::service {

::strata::v1::SceneAnalysis analyze_scene(const scene::Scene& scene);
// Whether instance `id` has emissive triangles at any of its LoD levels (moving it moves light).
bool instance_emits(const scene::Scene& scene, uint32_t id);

}  // namespace strata::service
