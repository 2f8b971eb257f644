#include "scene/gltf_export_skins.h"

#include <cstdint>
#include <limits>

#include "scene/gltf_extras.h"

namespace strata::scene::gltf {

void export_primitive_deformation(GlbBuilder& b, const Primitive& p, const std::string& field,
                                  tinygltf::Primitive& out) {
  if (!p.joints.empty()) {
    // glTF 2.0 3.7.3.3: JOINTS_0 is unsigned byte or unsigned short.
    std::vector<uint16_t> joints;
    joints.reserve(4 * p.joints.size());
    for (size_t v = 0; v < p.joints.size(); ++v) {
      for (int c = 0; c < 4; ++c) {
        if (p.joints[v][c] > std::numeric_limits<uint16_t>::max()) {
          throw SceneError("cannot export: " + field + ".joints[" + std::to_string(v) + "] names joint " +
                           std::to_string(p.joints[v][c]) + ", over 65535 (JOINTS_0 holds unsigned shorts)");
        }
        joints.push_back(static_cast<uint16_t>(p.joints[v][c]));
      }
    }
    out.attributes["JOINTS_0"] =
        b.accessor(joints, TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT, TINYGLTF_TYPE_VEC4, 4, kArray, false);
    out.attributes["WEIGHTS_0"] = b.accessor(p.weights, kFloat, TINYGLTF_TYPE_VEC4, 4, kArray, false);
  }
  // 3.7.2.2: a target's POSITION accessor carries min and max, like the base POSITION.
  for (const MorphTarget& target : p.targets) {
    std::map<std::string, int> attributes;
    attributes["POSITION"] = b.accessor(target.positions, kFloat, TINYGLTF_TYPE_VEC3, 3, kArray, true);
    if (!target.normals.empty())
      attributes["NORMAL"] = b.accessor(target.normals, kFloat, TINYGLTF_TYPE_VEC3, 3, kArray, false);
    out.targets.push_back(std::move(attributes));
  }
}

std::vector<std::vector<int>> export_skins(GlbBuilder& b, const Scene& s, std::vector<int>& roots) {
  tinygltf::Model& m = b.model();
  std::vector<std::vector<bool>> animated(s.skins.size());
  for (size_t k = 0; k < s.skins.size(); ++k) animated[k].assign(s.skins[k].joints.size(), false);
  for (const JointTrack& track : s.animation.joint_tracks)
    if (!track.keys.empty()) animated[track.skin][track.joint] = true;
  std::vector<std::vector<int>> joint_nodes(s.skins.size());
  for (size_t k = 0; k < s.skins.size(); ++k) {
    const Skin& skin = s.skins[k];
    const std::string prefix = skin.name.empty() ? "skin" + std::to_string(k) : skin.name;
    tinygltf::Node skeleton;
    skeleton.name = prefix + "_skeleton";
    m.nodes.push_back(skeleton);
    const int root = static_cast<int>(m.nodes.size() - 1);
    roots.push_back(root);
    tinygltf::Skin out;
    out.name = skin.name;
    out.skeleton = root;
    for (size_t j = 0; j < skin.joints.size(); ++j) {
      tinygltf::Node joint;
      joint.name = prefix + "_joint" + std::to_string(j);
      set_rest_transform(joint, skin.joints[j], animated[k][j]);
      if (animated[k][j]) joint.extras = rest_matrix_extras(skin.joints[j]);
      m.nodes.push_back(joint);
      const int node = static_cast<int>(m.nodes.size() - 1);
      m.nodes[static_cast<size_t>(root)].children.push_back(node);
      out.joints.push_back(node);
    }
    out.inverseBindMatrices = b.accessor(skin.inverse_bind, kFloat, TINYGLTF_TYPE_MAT4, 16, 0, false);
    m.skins.push_back(out);
    joint_nodes[k] = out.joints;
  }
  return joint_nodes;
}

}  // namespace strata::scene::gltf
