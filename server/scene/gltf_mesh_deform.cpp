#include "scene/gltf_mesh_deform.h"

#include <cmath>

#include "scene/gltf_accessor.h"

namespace strata::scene::gltf {
namespace {

// Accessor `index` for attribute `field`, its element count checked against POSITION's.
int checked_attribute(const Source& s, int index, const std::string& field, size_t vertices) {
  const size_t count = accessor_count(s, index, field);
  if (count != vertices) {
    s.fail(field, "has " + std::to_string(count) + " elements, POSITION has " + std::to_string(vertices));
  }
  return index;
}

bool starts_with(const std::string& s, const char* prefix) { return s.rfind(prefix, 0) == 0; }

}  // namespace

// glTF 2.0 3.7.3.3: JOINTS_0 is a VEC4 of unsigned byte or short joint indices into the skin's
// joints, WEIGHTS_0 a VEC4 of float or normalized unsigned byte or short weights, which must not
// be negative and sum to 1. More than 4 influences (JOINTS_1, WEIGHTS_1, ...) are refused: the
// deformation reads 4 per vertex. Weights whose sum is off 1 by more than 1e-3 (files rounded to few
// digits, or quantized without care) are divided by their sum rather than refused: the spec asks
// that they sum to 1 "as close as reasonably possible", and a skinning matrix blend that does not
// sum to 1 scales the vertex towards the origin. Sums within 1e-3 are kept bit for bit, so what
// export_glb writes loads back unchanged. A vertex whose weights are all 0 has no joint to follow and
// is refused.
size_t read_skin_attributes(const Source& s, const tinygltf::Primitive& p, const std::string& field,
                            size_t vertices, Primitive& out) {
  for (const auto& [name, accessor] : p.attributes) {
    if ((starts_with(name, "JOINTS_") || starts_with(name, "WEIGHTS_")) && name != "JOINTS_0" &&
        name != "WEIGHTS_0") {
      s.fail(field + ".attributes." + name,
             "is not supported: strata skins with at most 4 joint influences per vertex (JOINTS_0 "
             "and WEIGHTS_0)");
    }
  }
  const auto joints_it = p.attributes.find("JOINTS_0");
  const auto weights_it = p.attributes.find("WEIGHTS_0");
  const std::string joints_field = field + ".attributes.JOINTS_0";
  const std::string weights_field = field + ".attributes.WEIGHTS_0";
  if (joints_it == p.attributes.end() && weights_it == p.attributes.end()) return 0;
  if (joints_it == p.attributes.end()) s.fail(joints_field, "is missing (WEIGHTS_0 needs it)");
  if (weights_it == p.attributes.end()) s.fail(weights_field, "is missing (JOINTS_0 needs it)");
  out.joints = read_joints(s, checked_attribute(s, joints_it->second, joints_field, vertices), joints_field);
  const int weights = checked_attribute(s, weights_it->second, weights_field, vertices);
  const std::vector<float> w = read_floats(s, weights, 4, Components::kFloatOrNormalizedUnsigned, weights_field);
  const std::string name = weights_field + " (" + at("accessors", size_t(weights)) + ")";
  out.weights.resize(vertices);
  size_t renormalised = 0;
  for (size_t v = 0; v < vertices; ++v) {
    const glm::vec4 element(w[4 * v], w[4 * v + 1], w[4 * v + 2], w[4 * v + 3]);
    if (glm::any(glm::lessThan(element, glm::vec4(0.0f))))
      s.fail(name, "element " + std::to_string(v) + " has a negative weight (weights must be >= 0)");
    const double sum = double(element.x) + double(element.y) + double(element.z) + double(element.w);
    if (sum == 0.0)
      s.fail(name, "element " + std::to_string(v) + " has weights summing to 0 (a skinned vertex needs a joint)");
    if (std::abs(sum - 1.0) > 1e-3) {
      out.weights[v] = glm::vec4(glm::dvec4(element) / sum);
      ++renormalised;
    } else {
      out.weights[v] = element;
    }
  }
  return renormalised;
}

// glTF 2.0 3.7.2.2: a target holds per-vertex displacements of POSITION and NORMAL (and TANGENT,
// which strata leaves out: Scene::ignored_features says so). A target without POSITION displaces
// nothing; one without NORMAL leaves the normals alone.
void read_morph_targets(const Source& s, const tinygltf::Primitive& p, const std::string& field,
                        size_t vertices, size_t& target_vertices, Primitive& out) {
  if (p.targets.empty()) return;
  target_vertices += vertices * p.targets.size();
  if (target_vertices > kMaxMorphTargetVertices) {
    s.fail(field + ".targets", "bring the morph target vertex count (vertices x targets) to " +
                                   std::to_string(target_vertices) + ", over the limit of " +
                                   std::to_string(kMaxMorphTargetVertices));
  }
  for (size_t t = 0; t < p.targets.size(); ++t) {
    const std::string target_field = at(field + ".targets", t);
    MorphTarget target;
    for (const auto& [name, accessor] : p.targets[t]) {
      if (name != "POSITION" && name != "NORMAL") continue;
      const std::string attr_field = target_field + "." + name;
      const int index = checked_attribute(s, accessor, attr_field, vertices);
      (name == "POSITION" ? target.positions : target.normals) =
          read_vec3(s, index, Components::kFloatOnly, attr_field);
    }
    if (target.positions.empty()) target.positions.assign(vertices, glm::vec3(0.0f));
    out.targets.push_back(std::move(target));
  }
}

std::vector<float> read_mesh_weights(const Source& s, const tinygltf::Mesh& mesh, const std::string& field,
                                     const Mesh& out) {
  const size_t targets = out.primitives.empty() ? 0 : out.primitives[0].targets.size();
  for (size_t p = 1; p < out.primitives.size(); ++p) {
    if (out.primitives[p].targets.size() != targets) {
      s.fail(at(field + ".primitives", p) + ".targets",
             "has " + std::to_string(out.primitives[p].targets.size()) + " morph targets, primitives[0] has " +
                 std::to_string(targets) + " (every primitive of a mesh has the same number)");
    }
  }
  if (mesh.weights.empty()) return std::vector<float>(targets, 0.0f);
  if (mesh.weights.size() != targets) {
    s.fail(field + ".weights", "has " + std::to_string(mesh.weights.size()) + " entries, the mesh has " +
                                   std::to_string(targets) + " morph targets");
  }
  std::vector<float> weights;
  for (size_t t = 0; t < targets; ++t) {
    weights.push_back(to_float(mesh.weights[t]));
    if (!std::isfinite(weights.back())) s.fail(at(field + ".weights", t), "is not finite");
  }
  return weights;
}

}  // namespace strata::scene::gltf
