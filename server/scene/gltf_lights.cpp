// KHR_lights_punctual: the file's lights, one Scene light per node of the scene that carries one (a
// light on two nodes becomes two lights), in node order. A light's transform is its node's world
// transform; its node's animation becomes a LightTrack (gltf_animation.cpp). Values are checked
// here and named by their glTF field: colour and intensity finite and non-negative, range positive
// when given, spot cones with 0 <= innerConeAngle < outerConeAngle <= pi / 2.
#include <algorithm>
#include <cmath>

#include "scene/gltf_convert.h"
#include "scene/gltf_extras.h"

namespace strata::scene::gltf {
namespace {

constexpr const char* kLights = "KHR_lights_punctual";
constexpr double kHalfPi = 1.57079632679489661923;

std::string number(double v) {
  char buf[48];
  std::snprintf(buf, sizeof buf, "%g", v);
  return buf;
}

float checked(const Source& s, double value, const std::string& field, double lo, double hi) {
  const float f = to_float(value);
  if (!std::isfinite(f)) s.fail(field, "= " + number(value) + " is not a finite number");
  if (value < lo || value > hi)
    s.fail(field, "= " + number(value) + " is outside [" + number(lo) + ", " + number(hi) + "]");
  return f;
}

Light read_light(const Source& s, size_t index) {
  const tinygltf::Light& in = s.model.lights[index];
  const std::string field = std::string("extensions.") + kLights + "." + at("lights", index);
  Light out;
  out.name = in.name;
  if (in.type == "directional") {
    out.type = LightType::kDirectional;
  } else if (in.type == "point") {
    out.type = LightType::kPoint;
  } else if (in.type == "spot") {
    out.type = LightType::kSpot;
  } else {
    s.fail(field + ".type", "= '" + in.type + "' is not directional, point or spot");
  }
  if (!in.color.empty()) {
    if (in.color.size() != 3) s.fail(field + ".color", "must hold 3 numbers");
    for (size_t c = 0; c < 3; ++c) out.color[int(c)] = checked(s, in.color[c], at(field + ".color", c), 0.0, 1e30);
  }
  out.intensity = checked(s, in.intensity, field + ".intensity", 0.0, 1e30);
  // tinygltf reads an absent range as 0, which is also how Light says "unlimited".
  out.range = checked(s, in.range, field + ".range", 0.0, 1e30);
  if (out.type == LightType::kSpot) {
    out.inner_cone = checked(s, in.spot.innerConeAngle, field + ".spot.innerConeAngle", 0.0, kHalfPi);
    out.outer_cone = checked(s, in.spot.outerConeAngle, field + ".spot.outerConeAngle", 0.0, kHalfPi);
    if (!(out.inner_cone < out.outer_cone)) {
      s.fail(field + ".spot.innerConeAngle", "= " + number(in.spot.innerConeAngle) + " is not below outerConeAngle (" +
                                                 number(in.spot.outerConeAngle) + ")");
    }
  }
  return out;
}

// True when node `i` belongs to the scene being loaded (its root is one of the scene's roots).
bool in_scene(const Source& s, const NodeTree& tree, size_t i) {
  size_t root = i;
  for (size_t guard = 0; tree.parent[root] >= 0 && guard <= tree.parent.size(); ++guard)
    root = size_t(tree.parent[root]);
  if (tree.scene_index < 0) return true;
  const std::vector<int>& roots = s.model.scenes[size_t(tree.scene_index)].nodes;
  return std::find(roots.begin(), roots.end(), int(root)) != roots.end();
}

glm::mat4 world_of(const NodeTree& tree, size_t i) {
  glm::mat4 world = tree.local_matrix[i];
  for (int p = tree.parent[i]; p >= 0; p = tree.parent[size_t(p)]) world = tree.local_matrix[size_t(p)] * world;
  return world;
}

}  // namespace

void convert_lights(const Source& s, NodeTree& tree, Scene& scene) {
  std::vector<Light> lights;
  for (size_t i = 0; i < s.model.lights.size(); ++i) lights.push_back(read_light(s, i));
  for (size_t i = 0; i < s.model.nodes.size(); ++i) {
    const auto it = s.model.nodes[i].extensions.find(kLights);
    if (it == s.model.nodes[i].extensions.end()) continue;
    const std::string field = at("nodes", i) + ".extensions." + kLights + ".light";
    if (!it->second.IsObject() || !it->second.Has("light") || !it->second.Get("light").IsInt())
      s.fail(field, "must be an integer");
    const int light = it->second.Get("light").Get<int>();
    s.check_index(field, light, lights.size(), "lights");
    if (!in_scene(s, tree, i)) continue;
    if (scene.lights.size() >= s.limits.max_instances) {
      s.fail(field, "would be light " + std::to_string(scene.lights.size() + 1) + ", over LoadLimits::max_instances (" +
                        std::to_string(s.limits.max_instances) + ")");
    }
    Light out = lights[size_t(light)];
    // An animated light's exported node holds TRS and its exact rest matrix in extras (gltf_export.cpp).
    out.transform = read_node_extras(s, int(i)).rest_matrix.value_or(world_of(tree, i));
    if (out.name.empty()) out.name = s.model.nodes[i].name;
    scene.lights.push_back(std::move(out));
    tree.light_node.push_back(uint32_t(i));
  }
}

}  // namespace strata::scene::gltf
