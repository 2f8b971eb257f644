#include "scene/gltf_extras.h"

#include <cmath>
#include <cstring>

#include "scene/environment_map.h"

namespace strata::scene::gltf {
namespace {

using tinygltf::Value;

Value number(float f) {
  return Value(static_cast<double>(f));
}

Value vec3(const glm::vec3& v) {
  return Value(Value::Array{number(v.x), number(v.y), number(v.z)});
}

double read_number(const Source& s, const Value& v, const std::string& field) {
  if (!v.IsNumber()) s.fail(field, "must be a number");
  return v.GetNumberAsDouble();
}

uint32_t read_count(const Source& s, const Value& v, const std::string& field) {
  const double d = read_number(s, v, field);
  if (!(d >= 0.0 && d <= 4294967295.0) || std::floor(d) != d)
    s.fail(field, "must be a non-negative integer");
  return static_cast<uint32_t>(d);
}

// extras.strata of an object, or a null Value.
const Value& strata_object(const Value& extras) {
  static const Value kNull;
  if (!extras.IsObject() || !extras.Has("strata")) return kNull;
  return extras.Get("strata");
}

void read_lod_schedule(const Source& s, const Value& schedule, const std::string& field,
                       Scene& scene) {
  if (!schedule.IsArray()) s.fail(field, "must be an array");
  for (size_t k = 0; k < schedule.ArrayLen(); ++k) {
    const Value& key = schedule.Get(static_cast<int>(k));
    const std::string key_field = at(field, k);
    if (!key.IsArray() || key.ArrayLen() != 3) s.fail(key_field, "must be [time, instance, level]");
    scene.animation.lod_schedule.push_back(
        LodKey{to_float(read_number(s, key.Get(0), key_field + "[0]")),
               read_count(s, key.Get(1), key_field + "[1]"),
               read_count(s, key.Get(2), key_field + "[2]")});
  }
}

// An environment map written by export_environment_map (scene/gltf_export_textures.h): width x
// height texels of float32 RGB in a buffer view, finite and not negative, within the texture
// dimension limit.
void read_environment_map(const Source& s, const Value& v, const std::string& field, Scene& scene) {
  if (!v.IsObject()) s.fail(field, "must be an object");
  EnvironmentMap map;
  if (v.Has("name")) {
    if (!v.Get("name").IsString()) s.fail(field + ".name", "must be a string");
    map.name = v.Get("name").Get<std::string>();
  }
  map.width = v.Has("width") ? read_count(s, v.Get("width"), field + ".width") : 0;
  map.height = v.Has("height") ? read_count(s, v.Get("height"), field + ".height") : 0;
  if (map.width == 0 || map.height == 0 || map.width > s.limits.max_texture_dimension || map.height > s.limits.max_texture_dimension)
    s.fail(field, "is " + std::to_string(map.width) + " x " + std::to_string(map.height) + " texels (1 to " +
                      std::to_string(s.limits.max_texture_dimension) + " a side)");
  map.intensity = v.Has("intensity") ? to_float(read_number(s, v.Get("intensity"), field + ".intensity")) : 1.0f;
  map.rotation = v.Has("rotation") ? to_float(read_number(s, v.Get("rotation"), field + ".rotation")) : 0.0f;
  if (!std::isfinite(map.intensity) || map.intensity < 0.0f || !std::isfinite(map.rotation))
    s.fail(field, "needs a finite intensity >= 0 and a finite rotation");
  const int view = v.Has("bufferView") ? int(read_count(s, v.Get("bufferView"), field + ".bufferView")) : -1;
  s.check_index(field + ".bufferView", view, s.model.bufferViews.size(), "bufferViews");
  const tinygltf::BufferView& bv = s.model.bufferViews[size_t(view)];
  s.check_index(at("bufferViews", size_t(view)) + ".buffer", bv.buffer, s.model.buffers.size(), "buffers");
  const std::vector<unsigned char>& data = s.model.buffers[size_t(bv.buffer)].data;
  const size_t texels = size_t(map.width) * map.height;
  if (bv.byteLength != texels * 12 || bv.byteOffset > data.size() || bv.byteLength > data.size() - bv.byteOffset)
    s.fail(at("bufferViews", size_t(view)), "must hold the map's " + std::to_string(texels) + " float32 RGB texels within its buffer");
  map.radiance.resize(texels);
  for (size_t i = 0; i < texels; ++i) {
    float rgb[3];
    std::memcpy(rgb, data.data() + bv.byteOffset + 12 * i, sizeof rgb);
    for (int c = 0; c < 3; ++c)
      if (!std::isfinite(rgb[c]) || rgb[c] < 0.0f) s.fail(field, "texel " + std::to_string(i) + " is not finite and >= 0");
    map.radiance[i] = {rgb[0], rgb[1], rgb[2]};
  }
  build_environment_tables(map);
  scene.environment.map = std::move(map);
}

}  // namespace

Value scene_extras(const Scene& scene, const Value& environment_map) {
  Value::Array schedule;
  for (const LodKey& key : scene.animation.lod_schedule) {
    schedule.emplace_back(Value::Array{number(key.time), Value(static_cast<int>(key.instance)),
                                       Value(static_cast<int>(key.level))});
  }
  Value::Object strata{{"name", Value(scene.name)},
                       {"environment", vec3(scene.environment.radiance)},
                       {"aperture", number(scene.camera.aperture)},
                       {"focus_distance", number(scene.camera.focus_distance)},
                       {"frames_per_second", number(scene.animation.frames_per_second)}};
  if (!schedule.empty()) strata.emplace("lod_schedule", Value(std::move(schedule)));
  if (environment_map.IsObject()) strata["environment_map"] = environment_map;
  return Value(Value::Object{{"strata", Value(std::move(strata))}});
}

namespace {
Value matrix_value(const glm::mat4& matrix) {
  Value::Array m;
  for (int c = 0; c < 4; ++c) {
    for (int r = 0; r < 4; ++r) m.push_back(number(matrix[c][r]));
  }
  return Value(std::move(m));
}
}  // namespace

Value node_extras(const Instance& instance, bool write_rest_matrix) {
  Value::Object strata;
  if (instance.lod != 0) strata.emplace("lod", Value(static_cast<int>(instance.lod)));
  if (write_rest_matrix) strata.emplace("rest_matrix", matrix_value(instance.transform));
  if (strata.empty()) return Value();
  return Value(Value::Object{{"strata", Value(std::move(strata))}});
}

Value rest_matrix_extras(const glm::mat4& rest_matrix) {
  return Value(Value::Object{{"strata", Value(Value::Object{{"rest_matrix", matrix_value(rest_matrix)}})}});
}

bool read_scene_extras(const Source& s, int scene_index, Scene& scene) {
  if (scene_index < 0) return false;
  const Value& strata = strata_object(s.model.scenes[static_cast<size_t>(scene_index)].extras);
  if (!strata.IsObject()) return false;
  const std::string field = at("scenes", static_cast<size_t>(scene_index)) + ".extras.strata";
  // tinygltf drops empty strings, arrays and objects from extras, so every key is optional.
  if (strata.Has("name")) {
    if (!strata.Get("name").IsString()) s.fail(field + ".name", "must be a string");
    scene.name = strata.Get("name").Get<std::string>();
  }
  if (strata.Has("environment")) {
    const Value& e = strata.Get("environment");
    if (!e.IsArray() || e.ArrayLen() != 3) s.fail(field + ".environment", "must be [r, g, b]");
    for (int c = 0; c < 3; ++c) {
      scene.environment.radiance[c] = to_float(read_number(s, e.Get(c), field + ".environment"));
    }
  }
  if (strata.Has("environment_map"))
    read_environment_map(s, strata.Get("environment_map"), field + ".environment_map", scene);
  if (strata.Has("aperture"))
    scene.camera.aperture = to_float(read_number(s, strata.Get("aperture"), field + ".aperture"));
  if (strata.Has("focus_distance")) {
    scene.camera.focus_distance =
        to_float(read_number(s, strata.Get("focus_distance"), field + ".focus_distance"));
  }
  if (strata.Has("frames_per_second")) {
    scene.animation.frames_per_second =
        to_float(read_number(s, strata.Get("frames_per_second"), field + ".frames_per_second"));
  }
  if (strata.Has("lod_schedule"))
    read_lod_schedule(s, strata.Get("lod_schedule"), field + ".lod_schedule", scene);
  return true;
}

NodeExtras read_node_extras(const Source& s, int node) {
  NodeExtras out;
  const Value& strata = strata_object(s.model.nodes[static_cast<size_t>(node)].extras);
  if (!strata.IsObject()) return out;
  const std::string field = at("nodes", static_cast<size_t>(node)) + ".extras.strata";
  if (strata.Has("lod")) out.lod = read_count(s, strata.Get("lod"), field + ".lod");
  if (strata.Has("rest_matrix")) {
    const Value& m = strata.Get("rest_matrix");
    if (!m.IsArray() || m.ArrayLen() != 16) s.fail(field + ".rest_matrix", "must hold 16 numbers");
    glm::mat4 matrix;
    for (int i = 0; i < 16; ++i)
      matrix[i / 4][i % 4] = to_float(read_number(s, m.Get(i), field + ".rest_matrix"));
    out.rest_matrix = matrix;
  }
  return out;
}

}  // namespace strata::scene::gltf
