#pragma once
// The textured half of export_glb (scene/gltf_export.cpp): images (each texture image's finest
// level as an RGBA PNG; the reader rebuilds the same mip chain from it), samplers, textures, the
// materials' texture references with KHR_texture_transform, alpha modes, and the environment map,
// which glTF has no place for: it rides in the scene's extras (its radiance as float32 RGB in a
// buffer view), read back by gltf_extras.
#include <string>
#include <vector>

#include <tiny_gltf.h>

#include "scene/scene.h"

namespace strata::scene::gltf {

// A buffer view over `bytes`, appended to buffer 0 at a 4-byte boundary.
int append_view(tinygltf::Model& model, const uint8_t* bytes, size_t size);

// The set's images, one sampler per texture, and its textures, in the set's order.
void export_textures(tinygltf::Model& model, const TextureSet& set);

// Material `m`'s texture references, its base colour alpha, alpha mode and cutoff onto `out`; the
// extensions it uses are added to `used`.
void export_material_textures(const Material& m, tinygltf::Material& out, std::vector<std::string>& used);

// The environment map's record for the scene's extras (scene_extras), its radiance in a buffer view.
tinygltf::Value export_environment_map(tinygltf::Model& model, const EnvironmentMap& map);

}  // namespace strata::scene::gltf
