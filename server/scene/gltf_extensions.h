#pragma once
// Internal to the glTF loader: what strata does with each glTF extension. An extension is either
// rendered (its content reaches the scene model and the renderer), or it is not; a file that
// *requires* one that is not is refused by name, and one that merely *uses* it loads with the
// extension listed in Scene::ignored_features, together with the core glTF features the scene
// model leaves out (vertex colours, occlusion textures, morph target TANGENT deltas, ...).
#include <cstdint>
#include <span>
#include <string>
#include <string_view>

#include "scene/gltf_source.h"
#include "scene/scene.h"

namespace strata::scene::gltf {

// True for the extensions whose content strata renders.
bool is_rendered_extension(std::string_view name);

// Throws SceneError naming each entry of the document's top-level `extensionsRequired` that strata
// does not render. `json`: the glTF JSON text (a .glb's JSON chunk). Runs before tinygltf, whose
// own errors for such files (e.g. an accessor without a bufferView, as Draco leaves them) do not
// say why. JSON that does not parse is left to tinygltf to report.
void refuse_required_extensions(std::span<const uint8_t> json, const std::string& label);

// Appends to scene.ignored_features one phrase per extension the file uses that strata does not
// render ("KHR_materials_clearcoat on 3 materials") and per core feature left out ("COLOR_0 on 1
// primitive (vertex colours are not rendered)").
void list_ignored_features(const Source& source, Scene& scene);

// "1 material", "3 materials"; `plural` defaults to singular + "s".
std::string count_of(size_t count, std::string_view singular, std::string_view plural = {});

}  // namespace strata::scene::gltf
