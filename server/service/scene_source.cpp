#include "service/scene_source.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <span>

#include "scene/environment_map.h"
#include "scene/scene_io.h"
#include "service/errors.h"

namespace strata::service {
namespace {

namespace fs = std::filesystem;
using grpc::StatusCode;

constexpr size_t k_max_listed_files = 1000;

std::string joined(const std::vector<std::string>& items) {
  std::string s;
  for (const auto& i : items) s += (s.empty() ? "" : ", ") + i;
  return s;
}

scene::LoadLimits load_limits(const ServiceLimits& limits) {
  scene::LoadLimits l;
  l.max_file_bytes = limits.max_scene_bytes;
  l.max_instances = limits.max_instances;
  l.max_texture_bytes = limits.max_texture_bytes;
  return l;
}

// Decoded textures over max_texture_bytes or the largest texture dimension are RESOURCE_EXHAUSTED.
template <class Load>
scene::Scene within_resource_limits(Load&& load) {
  try {
    return load();
  } catch (const scene::SceneLimitError& e) {
    fail(StatusCode::RESOURCE_EXHAUSTED, e.what());
  }
}

std::string lower_extension(const fs::path& p) {
  auto ext = p.extension().string();
  std::transform(ext.begin(), ext.end(), ext.begin(), [](unsigned char c) { return char(std::tolower(c)); });
  return ext;
}

bool is_scene_file(const fs::path& p) {
  const std::string ext = lower_extension(p);
  return ext == ".gltf" || ext == ".glb";
}

bool is_environment_file(const fs::path& p) {
  const std::string ext = lower_extension(p);
  return ext == ".hdr" || ext == ".exr";
}

bool inside(const fs::path& path, const fs::path& root) {
  auto r = root.begin(), p = path.begin();
  for (; r != root.end(); ++r, ++p)
    if (p == path.end() || *p != *r) return false;
  return true;
}

// The canonical file a client's path (`field`) names, refused unless it lies inside the scene
// directory and is of the kind `accepted` admits (`kind` names it).
fs::path resolve_path(const std::string& requested, const ServiceConfig& config, const std::string& field = "scene.path",
                      bool (*accepted)(const fs::path&) = is_scene_file, const char* kind = "a .gltf or .glb file") {
  if (config.scene_dir.empty())
    fail(StatusCode::FAILED_PRECONDITION, field + " is refused: this server was started without a scene directory (--scene-dir)");
  if (requested.empty()) fail_invalid(field + " is empty");
  if (requested.size() > 4096) fail_invalid(field + " is " + std::to_string(requested.size()) + " characters long; at most 4096");
  if (requested.find('\0') != std::string::npos) fail_invalid(field + " contains a NUL character");
  if (!accepted(requested)) fail_invalid(field + " = '" + requested + "' is not " + kind);
  std::error_code ec;
  const fs::path root = fs::canonical(config.scene_dir, ec);
  if (ec) fail(StatusCode::FAILED_PRECONDITION, "the scene directory '" + config.scene_dir.string() + "' is not readable: " + ec.message());
  const fs::path asked(requested);
  const fs::path candidate = asked.is_absolute() ? asked : root / asked;
  const fs::path resolved = fs::weakly_canonical(candidate, ec);  // follows symbolic links
  if (ec) fail_invalid(field + " = '" + requested + "' cannot be resolved: " + ec.message());
  if (!inside(resolved, root))
    fail(StatusCode::PERMISSION_DENIED, field + " = '" + requested + "' resolves to '" + resolved.string() +
                                            "', outside the scene directory '" + root.string() + "'");
  if (!fs::exists(resolved, ec)) fail(StatusCode::NOT_FOUND, field + " = '" + requested + "' does not exist in the scene directory");
  if (!fs::is_regular_file(resolved, ec)) fail_invalid(field + " = '" + requested + "' is not a regular file");
  return resolved;
}

std::string number(double v) {
  char buf[48];
  std::snprintf(buf, sizeof buf, "%g", v);
  return buf;
}

// SceneSource.environment: an HDR image from the scene directory or inline, held to
// max_environment_bytes and max_environment_dimension (RESOURCE_EXHAUSTED past the dimension).
scene::EnvironmentMap load_environment_source(const v1::EnvironmentSource& source, const ServiceConfig& config) {
  const ServiceLimits& limits = config.limits;
  const std::string field = "scene.environment";
  scene::EnvironmentOptions options;
  options.max_file_bytes = limits.max_environment_bytes;
  options.max_dimension = limits.max_environment_dimension;
  if (source.has_intensity()) {
    if (!std::isfinite(source.intensity()) || source.intensity() < 0.0f)
      fail_invalid(field + ".intensity = " + number(source.intensity()) + " is not a finite number >= 0");
    options.intensity = source.intensity();
  }
  if (source.has_rotation_degrees()) {
    if (!std::isfinite(source.rotation_degrees()))
      fail_invalid(field + ".rotation_degrees = " + number(source.rotation_degrees()) + " is not finite");
    options.rotation_degrees = source.rotation_degrees();
  }
  const std::string max_bytes = std::to_string(limits.max_environment_bytes);
  try {
    switch (source.source_case()) {
      case v1::EnvironmentSource::kPath: {
        const fs::path file = resolve_path(source.path(), config, field + ".path", is_environment_file, "a .hdr or .exr file");
        const uint64_t size = fs::file_size(file);
        if (size > limits.max_environment_bytes)
          fail_invalid(field + ".path = '" + source.path() + "' is " + std::to_string(size) + " bytes; max_environment_bytes = " + max_bytes);
        return scene::load_environment_map(file, options);
      }
      case v1::EnvironmentSource::kImage: {
        const std::string& bytes = source.image();
        if (bytes.empty()) fail_invalid(field + ".image is empty");
        if (bytes.size() > limits.max_environment_bytes)
          fail_invalid(field + ".image is " + std::to_string(bytes.size()) + " bytes; max_environment_bytes = " + max_bytes);
        const std::string label = source.label().empty() ? "inline.hdr" : source.label();
        if (label.size() > 256) fail_invalid(field + ".label is " + std::to_string(label.size()) + " characters long; at most 256");
        std::span<const uint8_t> data(reinterpret_cast<const uint8_t*>(bytes.data()), bytes.size());
        return scene::decode_environment_map(data, field + ".image (" + label + ")", options);
      }
      default:
        fail_invalid(field + " is set without a source: set scene.environment.path or scene.environment.image");
    }
  } catch (const scene::SceneLimitError& e) {
    fail(StatusCode::RESOURCE_EXHAUSTED, e.what() + std::string(" (max_environment_dimension)"));
  } catch (const scene::SceneError& e) {
    fail_invalid(e.what());
  }
}

}  // namespace

std::shared_ptr<const scene::Scene> load_scene_source(const v1::SceneSource& source, const ServiceConfig& config) {
  const ServiceLimits& limits = config.limits;
  const std::string max_bytes = std::to_string(limits.max_scene_bytes);
  auto s = std::make_shared<scene::Scene>();
  switch (source.source_case()) {
    case v1::SceneSource::kBuiltin:
      if (!scene::is_builtin_scene(source.builtin()))
        fail_invalid("scene.builtin = '" + source.builtin() + "' is not a built-in scene; built-in scenes: " +
                     joined(scene::builtin_scene_names()));
      *s = scene::builtin_scene(source.builtin());
      break;
    case v1::SceneSource::kPath: {
      const fs::path file = resolve_path(source.path(), config);
      const uint64_t size = fs::file_size(file);
      if (size > limits.max_scene_bytes)
        fail_invalid("scene.path = '" + source.path() + "' is " + std::to_string(size) + " bytes; max_scene_bytes = " + max_bytes);
      *s = within_resource_limits([&] { return scene::load_gltf_file(file, load_limits(limits)); });
      break;
    }
    case v1::SceneSource::kGlb: {
      const std::string& bytes = source.glb();
      if (bytes.empty()) fail_invalid("scene.glb is empty");
      if (bytes.size() > limits.max_scene_bytes)
        fail_invalid("scene.glb is " + std::to_string(bytes.size()) + " bytes; max_scene_bytes = " + max_bytes);
      const std::string label = source.label().empty() ? "inline.glb" : source.label();
      if (label.size() > 256) fail_invalid("scene.label is " + std::to_string(label.size()) + " characters long; at most 256");
      std::span<const uint8_t> data(reinterpret_cast<const uint8_t*>(bytes.data()), bytes.size());
      *s = within_resource_limits([&] { return scene::load_glb_bytes(data, "scene.glb (" + label + ")", load_limits(limits)); });
      if (s->name.empty()) s->name = label;
      break;
    }
    default:
      fail_invalid("scene is required: set scene.builtin, scene.path or scene.glb");
  }
  if (s->instances.size() > limits.max_instances)
    fail_invalid("scene '" + s->name + "' has " + std::to_string(s->instances.size()) + " instances; max_instances = " +
                 std::to_string(limits.max_instances));
  if (s->instances.empty()) fail_invalid("scene '" + s->name + "' has no instances: nothing to render");
  if (source.has_environment()) s->environment.map = load_environment_source(source.environment(), config);
  return s;
}

std::vector<v1::SceneEntry> list_scenes(const ServiceConfig& config) {
  std::vector<v1::SceneEntry> out;
  for (const auto& name : scene::builtin_scene_names()) {
    v1::SceneEntry e;
    e.set_name(name);
    e.set_kind(v1::SceneEntry::BUILTIN);
    out.push_back(std::move(e));
  }
  if (config.scene_dir.empty()) return out;
  std::error_code ec;
  const fs::path root = fs::canonical(config.scene_dir, ec);
  if (ec) return out;
  std::vector<v1::SceneEntry> files;
  fs::recursive_directory_iterator it(root, fs::directory_options::skip_permission_denied, ec), end;
  for (; !ec && it != end && files.size() < k_max_listed_files; it.increment(ec)) {
    if (it.depth() > 8) {
      it.disable_recursion_pending();
      continue;
    }
    std::error_code fe;
    if (!it->is_regular_file(fe) || !is_scene_file(it->path())) continue;
    v1::SceneEntry e;
    e.set_name(fs::relative(it->path(), root, fe).string());
    e.set_kind(v1::SceneEntry::FILE);
    e.set_size_bytes(it->file_size(fe));
    files.push_back(std::move(e));
  }
  std::sort(files.begin(), files.end(), [](const auto& a, const auto& b) { return a.name() < b.name(); });
  for (auto& f : files) out.push_back(std::move(f));
  return out;
}

}  // namespace strata::service
