#pragma once
// Reading, writing and naming scenes.
#include <cstdint>
#include <filesystem>
#include <span>
#include <string>
#include <vector>

#include "scene/scene.h"

namespace strata::scene {

// Limits applied to every loaded file; exceeding one is a SceneError naming the limit.
struct LoadLimits {
  uint64_t max_file_bytes = 512ull << 20;
  uint64_t max_triangles = 8'000'000;
  uint32_t max_instances = 65'536;
  uint32_t max_lod_levels = 8;
  // Decoded textures: every texel of every mip level as RGBA8 (the device holds them as linear
  // RGBA16, twice that), and the longest side of one image.
  // Exceeding either is a SceneLimitError naming it.
  uint64_t max_texture_bytes = 1ull << 30;
  uint32_t max_texture_dimension = 8192;
};

// glTF 2.0 (.gltf with external or embedded buffers, or .glb). Throws SceneError.
Scene load_gltf_file(const std::filesystem::path& path, const LoadLimits& limits = {});
// A .glb held in memory (e.g. sent inline by a client). `label` names it in error messages.
Scene load_glb_bytes(std::span<const uint8_t> bytes, const std::string& label,
                     const LoadLimits& limits = {});

// Writes the scene as .glb: MSFT_lod for LoD groups, glTF animations for the default animation,
// strata-specific data (aperture, focus distance, environment, LoD schedule) in `extras`.
// load_glb_bytes(export_glb(s)) == s for every built-in scene. Punctual lights are written
// (KHR_lights_punctual, one node each at its rest transform, their tracks as animation channels);
// textures (each image's finest level as PNG), samplers, KHR_texture_transform and alpha modes;
// skins (joints as nodes at their rest transforms), JOINTS_0 / WEIGHTS_0, morph targets, mesh and
// node weights, joint and morph tracks; the environment map in `extras`. Scene::ignored_features are not written (no built-in scene has
// them).
std::vector<uint8_t> export_glb(const Scene& scene);
void export_glb_file(const Scene& scene, const std::filesystem::path& path);

// Deterministic procedural scenes: cornell (the default), cornell-lamps, carousel, carousel-bounce,
// lod-cliff, chess, foliage, overlap-uv, stiff, lod-bounce, courtyard, night-street, atrium,
// characters (scene/builtin/).
std::vector<std::string> builtin_scene_names();
bool is_builtin_scene(const std::string& name);
Scene builtin_scene(const std::string& name);  // throws SceneError for an unknown name

// A built-in name, or else a path to a .gltf/.glb file.
Scene load_scene(const std::string& name_or_path, const LoadLimits& limits = {});

}  // namespace strata::scene
