#pragma once
// Where a session's scene comes from: a built-in name, a file inside the allow-listed scene
// directory, or inline .glb bytes; each held to the server's limits.
#include <memory>
#include <vector>

#include "scene/scene.h"
#include "service/config.h"
#include "strata/v1/render.pb.h"

namespace strata::service {

// Throws ServiceError: INVALID_ARGUMENT (unknown name, bad or oversize file, too many instances),
// PERMISSION_DENIED (a path outside the scene directory), NOT_FOUND (no such file),
// FAILED_PRECONDITION (paths sent to a server without a scene directory).
std::shared_ptr<const scene::Scene> load_scene_source(const ::strata::v1::SceneSource& source, const ServiceConfig& config);

// Built-in scenes, then the .gltf/.glb files under the scene directory (at most 1000, sorted).
std::vector<::strata::v1::SceneEntry> list_scenes(const ServiceConfig& config);

}  // namespace strata::service
