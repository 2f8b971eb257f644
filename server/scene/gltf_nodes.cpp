// The glTF node hierarchy to Scene instances and camera. Only the nodes of the default scene
// (else scene 0, else every root node when the file has no scenes) are used; world transforms
// are flattened into Instance::transform. MSFT_lod: a node's `ids` name the nodes whose meshes
// are its coarser levels; those nodes lend their mesh only (their transforms are not used) and
// do not become instances themselves.
#include <cmath>
#include <limits>

#include "scene/gltf_convert.h"
#include "scene/gltf_extras.h"
#include "scene/transform.h"

namespace strata::scene::gltf {
namespace {

const char* kLodExtension = "MSFT_lod";

void read_local_transform(const Source& s, size_t i, NodeTree& tree) {
  const tinygltf::Node& node = s.model.nodes[i];
  const std::string field = at("nodes", i);
  if (!node.matrix.empty()) {
    if (node.matrix.size() != 16) s.fail(field + ".matrix", "must hold 16 numbers");
    glm::mat4 m;
    for (int k = 0; k < 16; ++k) m[k / 4][k % 4] = to_float(node.matrix[static_cast<size_t>(k)]);
    tree.local_matrix[i] = m;
    tree.local_trs[i] = decompose_trs(m);
    return;
  }
  TransformKey& trs = tree.local_trs[i];
  if (!node.translation.empty()) {
    if (node.translation.size() != 3) s.fail(field + ".translation", "must hold 3 numbers");
    trs.translation = {to_float(node.translation[0]), to_float(node.translation[1]),
                       to_float(node.translation[2])};
  }
  if (!node.rotation.empty()) {
    if (node.rotation.size() != 4) s.fail(field + ".rotation", "must hold 4 numbers");
    trs.rotation = read_rotation(s, node.rotation[0], node.rotation[1], node.rotation[2],
                                 node.rotation[3], field + ".rotation");
  }
  if (!node.scale.empty()) {
    if (node.scale.size() != 3) s.fail(field + ".scale", "must hold 3 numbers");
    trs.scale = {to_float(node.scale[0]), to_float(node.scale[1]), to_float(node.scale[2])};
  }
  tree.local_matrix[i] = compose_trs(trs);
}

// Parents of every node; glTF requires a forest, so a second parent is an error.
void link_parents(const Source& s, NodeTree& tree) {
  for (size_t i = 0; i < s.model.nodes.size(); ++i) {
    const std::vector<int>& children = s.model.nodes[i].children;
    for (size_t k = 0; k < children.size(); ++k) {
      const std::string field = at(at("nodes", i) + ".children", k);
      s.check_index(field, children[k], s.model.nodes.size(), "nodes");
      int& parent = tree.parent[static_cast<size_t>(children[k])];
      if (parent != -1 || children[k] == static_cast<int>(i)) {
        s.fail(field, "= " + std::to_string(children[k]) +
                          " already has a parent (node hierarchies must be trees)");
      }
      parent = static_cast<int>(i);
    }
  }
}

std::vector<int> root_nodes(const Source& s, NodeTree& tree) {
  const tinygltf::Model& m = s.model;
  std::vector<int> roots;
  if (m.scenes.empty()) {
    for (size_t i = 0; i < m.nodes.size(); ++i) {
      if (tree.parent[i] == -1) roots.push_back(static_cast<int>(i));
    }
    return roots;
  }
  if (m.defaultScene >= 0) s.check_index("scene", m.defaultScene, m.scenes.size(), "scenes");
  tree.scene_index = m.defaultScene >= 0 ? m.defaultScene : 0;
  roots = m.scenes[static_cast<size_t>(tree.scene_index)].nodes;
  for (size_t k = 0; k < roots.size(); ++k) {
    const std::string field = at(at("scenes", static_cast<size_t>(tree.scene_index)) + ".nodes", k);
    s.check_index(field, roots[k], m.nodes.size(), "nodes");
    if (tree.parent[static_cast<size_t>(roots[k])] != -1)
      s.fail(field, "= " + std::to_string(roots[k]) + " is not a root node");
  }
  return roots;
}

// The nodes under `roots`, parents before children (iterative: hierarchies may be deep).
std::vector<int> depth_first(const Source& s, const std::vector<int>& roots) {
  std::vector<int> order;
  std::vector<bool> seen(s.model.nodes.size(), false);
  std::vector<int> stack(roots.rbegin(), roots.rend());
  while (!stack.empty()) {
    const int node = stack.back();
    stack.pop_back();
    if (seen[static_cast<size_t>(node)])
      s.fail(at("nodes", static_cast<size_t>(node)), "is listed twice in the scene");
    seen[static_cast<size_t>(node)] = true;
    order.push_back(node);
    const std::vector<int>& children = s.model.nodes[static_cast<size_t>(node)].children;
    stack.insert(stack.end(), children.rbegin(), children.rend());
  }
  return order;
}

// The MSFT_lod ids of node `i` (empty without the extension), checked.
std::vector<int> lod_ids(const Source& s, size_t i) {
  const tinygltf::Node& node = s.model.nodes[i];
  const auto it = node.extensions.find(kLodExtension);
  if (it == node.extensions.end()) return {};
  const std::string field = at("nodes", i) + ".extensions." + kLodExtension + ".ids";
  if (!it->second.IsObject() || !it->second.Has("ids") || !it->second.Get("ids").IsArray())
    s.fail(field, "is missing");
  const tinygltf::Value& ids = it->second.Get("ids");
  std::vector<int> out;
  for (size_t k = 0; k < ids.ArrayLen(); ++k) {
    const tinygltf::Value& id = ids.Get(static_cast<int>(k));
    if (!id.IsInt()) s.fail(at(field, k), "must be an integer");
    s.check_index(at(field, k), id.Get<int>(), s.model.nodes.size(), "nodes");
    if (s.model.nodes[static_cast<size_t>(id.Get<int>())].mesh < 0) {
      s.fail(at(field, k), "= " + std::to_string(id.Get<int>()) + " names a node without a mesh");
    }
    out.push_back(id.Get<int>());
  }
  if (node.mesh < 0)
    s.fail(at("nodes", i) + ".extensions." + kLodExtension, "is on a node without a mesh");
  if (out.size() + 1 > s.limits.max_lod_levels) {
    s.fail(field, "gives " + std::to_string(out.size() + 1) +
                      " LoD levels, over LoadLimits::max_lod_levels (" +
                      std::to_string(s.limits.max_lod_levels) + ")");
  }
  return out;
}

// The transforms of every skin's joints and of their ancestors that lie outside the scene (a joint
// need not be one of the scene's nodes), parents first, so that tree.world holds every joint's.
void read_joint_chains(const Source& s, std::vector<bool>& placed, NodeTree& tree) {
  const size_t n = s.model.nodes.size();
  for (size_t k = 0; k < s.model.skins.size(); ++k) {
    const std::vector<int>& joints = s.model.skins[k].joints;
    for (size_t j = 0; j < joints.size(); ++j) {
      s.check_index(at(at("skins", k) + ".joints", j), joints[j], n, "nodes");
      std::vector<int> chain;  // the joint, then its ancestors up to the first one placed
      for (int node = joints[j]; node >= 0 && !placed[size_t(node)]; node = tree.parent[size_t(node)]) {
        if (chain.size() == n)
          s.fail(at("nodes", size_t(joints[j])), "is its own ancestor (node hierarchies must be trees)");
        chain.push_back(node);
      }
      for (auto it = chain.rbegin(); it != chain.rend(); ++it) {
        const size_t i = size_t(*it);
        read_local_transform(s, i, tree);
        const int parent = tree.parent[i];
        tree.world[i] = parent < 0 ? tree.local_matrix[i] : tree.world[size_t(parent)] * tree.local_matrix[i];
        placed[i] = true;
      }
    }
  }
}

// A camera framing every instance from +Z, for files without one.
Camera framing_camera(const Scene& scene) {
  glm::vec3 lo(std::numeric_limits<float>::max()), hi(-std::numeric_limits<float>::max());
  for (const Instance& instance : scene.instances) {
    for (const Primitive& p : scene.meshes[instance.lod_meshes[0]].primitives) {
      for (const glm::vec3& v : p.positions) {
        const glm::vec3 w = glm::vec3(instance.transform * glm::vec4(v, 1.0f));
        lo = glm::min(lo, w);
        hi = glm::max(hi, w);
      }
    }
  }
  Camera camera;
  if (!(lo.x <= hi.x)) return camera;  // nothing to frame
  const glm::vec3 center = 0.5f * (lo + hi);
  const float radius = std::max(0.5f * glm::length(hi - lo), 1e-3f);
  const float distance = radius / std::sin(0.5f * camera.yfov);
  camera.position = center + glm::vec3(0.0f, 0.0f, distance);
  camera.focus_distance = distance;
  return camera;
}

}  // namespace

glm::quat read_rotation(const Source& s, double x, double y, double z, double w,
                        const std::string& field) {
  glm::quat q(to_float(w), to_float(x), to_float(y), to_float(z));
  const float length = glm::length(q);
  if (!std::isfinite(length) || length < 1e-6f) s.fail(field, "is not a valid rotation quaternion");
  if (std::abs(length - 1.0f) > 1e-3f) q /= length;
  return q;
}

NodeTree convert_nodes(const Source& s, Scene& scene) {
  const size_t n = s.model.nodes.size();
  NodeTree tree;
  tree.parent.assign(n, -1);
  tree.local_trs.assign(n, TransformKey{});
  tree.local_matrix.assign(n, glm::mat4(1.0f));
  link_parents(s, tree);
  const std::vector<int> order = depth_first(s, root_nodes(s, tree));

  tree.world.assign(n, glm::mat4(1.0f));
  std::vector<glm::mat4>& world = tree.world;
  std::vector<bool> placed(n, false);
  std::vector<std::vector<int>> lods(n);
  std::vector<bool> is_lod_level(n, false);
  for (int node : order) {
    const size_t i = static_cast<size_t>(node);
    read_local_transform(s, i, tree);
    const int parent = tree.parent[i];
    world[i] = parent < 0 ? tree.local_matrix[i]
                          : world[static_cast<size_t>(parent)] * tree.local_matrix[i];
    lods[i] = lod_ids(s, i);
    for (int id : lods[i]) is_lod_level[static_cast<size_t>(id)] = true;
    placed[i] = true;
  }
  read_joint_chains(s, placed, tree);

  bool have_camera = false;
  for (int node : order) {
    const size_t i = static_cast<size_t>(node);
    const tinygltf::Node& gnode = s.model.nodes[i];
    const std::string field = at("nodes", i);
    if (gnode.mesh >= 0 && !is_lod_level[i]) {
      s.check_index(field + ".mesh", gnode.mesh, scene.meshes.size(), "meshes");
      if (scene.instances.size() >= s.limits.max_instances) {
        s.fail(field, "would be instance " + std::to_string(scene.instances.size() + 1) +
                          ", over LoadLimits::max_instances (" +
                          std::to_string(s.limits.max_instances) + ")");
      }
      const NodeExtras extras = read_node_extras(s, node);
      Instance instance;
      instance.name = gnode.name;
      instance.lod_meshes.push_back(static_cast<uint32_t>(gnode.mesh));
      for (int id : lods[i]) {
        const int mesh = s.model.nodes[static_cast<size_t>(id)].mesh;
        s.check_index(at("nodes", static_cast<size_t>(id)) + ".mesh", mesh, scene.meshes.size(),
                      "meshes");
        instance.lod_meshes.push_back(static_cast<uint32_t>(mesh));
      }
      instance.transform = extras.rest_matrix.value_or(world[i]);
      instance.lod = extras.lod;
      scene.instances.push_back(std::move(instance));
      tree.instance_node.push_back(static_cast<uint32_t>(node));
    } else if (gnode.mesh < -1) {
      s.check_index(field + ".mesh", gnode.mesh, scene.meshes.size(), "meshes");
    }
    if (gnode.camera != -1)
      s.check_index(field + ".camera", gnode.camera, s.model.cameras.size(), "cameras");
    if (gnode.camera >= 0 && !have_camera &&
        s.model.cameras[static_cast<size_t>(gnode.camera)].type == "perspective") {
      have_camera = true;
      tree.camera_node = node;
      // A root node's own TRS is used as is (exact); elsewhere the world matrix is decomposed.
      const bool root_trs = tree.parent[i] < 0 && gnode.matrix.empty();
      scene.camera.position = root_trs ? tree.local_trs[i].translation : glm::vec3(world[i][3]);
      scene.camera.orientation =
          root_trs ? tree.local_trs[i].rotation : decompose_trs(world[i]).rotation;
      scene.camera.yfov =
          to_float(s.model.cameras[static_cast<size_t>(gnode.camera)].perspective.yfov);
    }
  }
  if (!have_camera) scene.camera = framing_camera(scene);
  return tree;
}

}  // namespace strata::scene::gltf
