// glTF skins (glTF 2.0 3.7.3) to Scene::skins, and what each instance's node says about deforming
// its mesh: its skin (node.skin) and its morph weights (node.weights, else mesh.weights; 3.7.2.2).
// glTF skin k is Scene skin k. A skin's joints are its nodes' world transforms at rest (the exact
// matrix of extras.strata.rest_matrix where export_glb wrote one); the skinned node's own transform
// drops out of the skinning (scene.h, Skin), as 3.7.3 asks. A deforming instance keeps one LoD
// level: MSFT_lod on a skinned or morphing node is refused.
#include <cmath>

#include "scene/gltf_accessor.h"
#include "scene/gltf_convert.h"
#include "scene/gltf_extras.h"

namespace strata::scene::gltf {
namespace {

// Below this |determinant| an inverse bind matrix is taken as singular: it would collapse the
// skinned vertices onto a plane, line or point.
constexpr double kMinDeterminant = 1e-12;

Skin convert_skin(const Source& s, const NodeTree& tree, size_t k) {
  const tinygltf::Skin& skin = s.model.skins[k];
  const std::string field = at("skins", k);
  if (skin.joints.empty()) s.fail(field + ".joints", "is empty (a skin needs at least one joint)");
  if (skin.skeleton != -1) s.check_index(field + ".skeleton", skin.skeleton, s.model.nodes.size(), "nodes");
  Skin out;
  out.name = skin.name;
  for (size_t j = 0; j < skin.joints.size(); ++j) {
    const int node = skin.joints[j];
    s.check_index(at(field + ".joints", j), node, s.model.nodes.size(), "nodes");
    out.joints.push_back(read_node_extras(s, node).rest_matrix.value_or(tree.world[size_t(node)]));
  }
  // 3.7.3.1: without inverseBindMatrices every matrix is the identity; the accessor holds at least
  // one matrix per joint (extra ones are not used).
  if (skin.inverseBindMatrices == -1) {
    out.inverse_bind.assign(skin.joints.size(), glm::mat4(1.0f));
    return out;
  }
  const std::string ibm_field = field + ".inverseBindMatrices";
  out.inverse_bind = read_mat4(s, skin.inverseBindMatrices, ibm_field);
  if (out.inverse_bind.size() < skin.joints.size()) {
    s.fail(ibm_field, "has " + std::to_string(out.inverse_bind.size()) + " matrices, " + field + ".joints has " +
                          std::to_string(skin.joints.size()) + " (one per joint is needed)");
  }
  out.inverse_bind.resize(skin.joints.size());
  for (size_t j = 0; j < out.inverse_bind.size(); ++j) {
    const double det = glm::determinant(glm::dmat4(out.inverse_bind[j]));
    if (!(std::abs(det) >= kMinDeterminant)) {
      s.fail(ibm_field + " (" + at("accessors", size_t(skin.inverseBindMatrices)) + ")",
             "matrix " + std::to_string(j) + " is not invertible (|determinant| = " + std::to_string(std::abs(det)) +
                 ", below " + std::to_string(kMinDeterminant) + ")");
    }
  }
  return out;
}

// A skinned mesh needs JOINTS_0 and WEIGHTS_0 on every primitive, naming joints of its skin.
void check_skinned_mesh(const Source& s, const Scene& scene, uint32_t mesh, size_t node, size_t skin) {
  const std::string skin_name = at("skins", skin);
  const size_t joint_count = scene.skins[skin].joints.size();
  for (size_t p = 0; p < scene.meshes[mesh].primitives.size(); ++p) {
    const Primitive& primitive = scene.meshes[mesh].primitives[p];
    const std::string field = at(at("meshes", mesh) + ".primitives", p) + ".attributes.JOINTS_0";
    if (primitive.joints.empty()) {
      s.fail(field, "is missing (" + at("nodes", node) + " skins " + at("meshes", mesh) + " with " + skin_name +
                        "; a skinned mesh needs JOINTS_0 and WEIGHTS_0)");
    }
    for (size_t v = 0; v < primitive.joints.size(); ++v) {
      for (int c = 0; c < 4; ++c) {
        if (primitive.joints[v][c] >= joint_count) {
          s.fail(field, "element " + std::to_string(v) + " names joint " + std::to_string(primitive.joints[v][c]) +
                            ", but " + skin_name + " has " + std::to_string(joint_count) + " joints (" +
                            at("nodes", node) + " skins the mesh with it)");
        }
      }
    }
  }
}

// node.weights (3.7.2.2: they override mesh.weights), else the mesh's.
std::vector<float> morph_weights(const Source& s, const Scene& scene, uint32_t mesh, size_t node) {
  const tinygltf::Node& gnode = s.model.nodes[node];
  const size_t targets = scene.meshes[mesh].weights.size();
  if (gnode.weights.empty()) return scene.meshes[mesh].weights;
  const std::string field = at("nodes", node) + ".weights";
  if (gnode.weights.size() != targets) {
    s.fail(field, "has " + std::to_string(gnode.weights.size()) + " entries, " + at("meshes", mesh) + " has " +
                      std::to_string(targets) + " morph targets");
  }
  std::vector<float> out;
  for (size_t t = 0; t < targets; ++t) {
    out.push_back(to_float(gnode.weights[t]));
    if (!std::isfinite(out.back())) s.fail(at(field, t), "is not finite");
  }
  return out;
}

}  // namespace

void convert_skins(const Source& s, const NodeTree& tree, Scene& scene) {
  for (size_t k = 0; k < s.model.skins.size(); ++k) scene.skins.push_back(convert_skin(s, tree, k));
  for (size_t i = 0; i < scene.instances.size(); ++i) {
    Instance& instance = scene.instances[i];
    const size_t node = tree.instance_node[i];
    const tinygltf::Node& gnode = s.model.nodes[node];
    const uint32_t mesh = instance.lod_meshes[0];
    if (gnode.skin != -1) {
      s.check_index(at("nodes", node) + ".skin", gnode.skin, scene.skins.size(), "skins");
      check_skinned_mesh(s, scene, mesh, node, size_t(gnode.skin));
      instance.skin = gnode.skin;
    }
    instance.morph_weights = morph_weights(s, scene, mesh, node);
    if (instance.lod_meshes.size() < 2) continue;
    const std::string lod_field = at("nodes", node) + ".extensions.MSFT_lod";
    if (instance.deforms()) {
      s.fail(lod_field, std::string("is on a ") + (instance.skin >= 0 ? "skinned" : "morphing") +
                            " node (a deforming instance has one LoD level)");
    }
    for (size_t l = 1; l < instance.lod_meshes.size(); ++l) {
      if (!scene.meshes[instance.lod_meshes[l]].weights.empty()) {
        s.fail(at(lod_field + ".ids", l - 1), "names a node whose mesh has morph targets (a deforming instance "
                                              "has one LoD level)");
      }
    }
  }
}

}  // namespace strata::scene::gltf
