// Names of the built-in scenes and load_scene, the one entry point for "name or path".
#include <array>
#include <filesystem>
#include <utility>

#include "scene/builtin/builtins.h"
#include "scene/scene_io.h"

namespace strata::scene {
namespace {

using Generator = Scene (*)();
// The order is the order builtin_scene_names() reports; cornell, the default, comes first. The
// textured scenes (courtyard, night-street, atrium) stand together: they run the same textured,
// alpha-tested pipelines, and a test that renders every built-in in this order on lavapipe then
// reuses them. With another scene between them lavapipe compiled them again (restir.finite:
// night-street after characters took 358 s, right after courtyard 0.4 s).
constexpr std::array<std::pair<const char*, Generator>, 14> kBuiltins = {{
    {"cornell", builtin::make_cornell},
    {"cornell-lamps", builtin::make_cornell_lamps},
    {"carousel", builtin::make_carousel},
    {"carousel-bounce", builtin::make_carousel_bounce},
    {"lod-cliff", builtin::make_lod_cliff},
    {"chess", builtin::make_chess},
    {"foliage", builtin::make_foliage},
    {"overlap-uv", builtin::make_overlap_uv},
    {"stiff", builtin::make_stiff},
    {"lod-bounce", builtin::make_lod_bounce},
    {"courtyard", builtin::make_courtyard},
    {"night-street", builtin::make_night_street},
    {"atrium", builtin::make_atrium},
    {"characters", builtin::make_characters},
}};

}  // namespace

std::vector<std::string> builtin_scene_names() {
  std::vector<std::string> names;
  for (const auto& [name, generator] : kBuiltins) names.emplace_back(name);
  return names;
}

bool is_builtin_scene(const std::string& name) {
  for (const auto& [builtin_name, generator] : kBuiltins) {
    if (name == builtin_name) return true;
  }
  return false;
}

Scene builtin_scene(const std::string& name) {
  for (const auto& [builtin_name, generator] : kBuiltins) {
    if (name != builtin_name) continue;
    Scene scene = generator();
    try {
      scene.validate();
    } catch (const SceneError& e) {
      throw SceneError("built-in scene '" + name + "': " + e.what());
    }
    return scene;
  }
  std::string known;
  for (const auto& [builtin_name, generator] : kBuiltins)
    known += std::string(known.empty() ? "" : ", ") + builtin_name;
  throw SceneError("unknown built-in scene '" + name + "' (known: " + known + ")");
}

Scene load_scene(const std::string& name_or_path, const LoadLimits& limits) {
  if (is_builtin_scene(name_or_path)) return builtin_scene(name_or_path);
  // Something that is neither a built-in name nor a glTF path was most likely a mistyped name.
  const std::filesystem::path path(name_or_path);
  const std::string ext = path.extension().string();
  if (ext != ".gltf" && ext != ".glb" && !std::filesystem::exists(path)) {
    std::string names;
    for (const auto& n : builtin_scene_names()) names += (names.empty() ? "" : ", ") + n;
    throw SceneError("scene '" + name_or_path + "' is neither a built-in scene (" + names +
                     ") nor a .gltf/.glb file");
  }
  return load_gltf_file(name_or_path, limits);
}

}  // namespace strata::scene
