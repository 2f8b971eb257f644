#pragma once
// Internal to the glTF loader: the steps from a tinygltf::Model to a Scene, in the order
// gltf_load.cpp runs them. Each throws SceneError naming the glTF field at fault.
#include <optional>
#include <vector>

#include "scene/gltf_source.h"
#include "scene/scene.h"

namespace strata::scene::gltf {

// Every glTF material, in order (gltf_mesh.cpp).
void convert_materials(const Source& source, Scene& scene);
// Alpha modes and textures of every material (gltf_textures.cpp): decodes the images the
// materials use into scene.textures, with their mip chains, within LoadLimits' texture limits.
// Runs after convert_materials.
void convert_material_textures(const Source& source, Scene& scene);
// Every glTF mesh, in order, so glTF mesh i is Scene mesh i. Primitives without a material get a
// default material appended to scene.materials (gltf_mesh.cpp).
void convert_meshes(const Source& source, Scene& scene);

// The node hierarchy of the scene being loaded (gltf_nodes.cpp).
struct NodeTree {
  int scene_index = -1;                 // the glTF scene used; -1 when the file has none
  std::vector<int> parent;              // per node; -1 for roots
  std::vector<TransformKey> local_trs;  // per node: its TRS (a matrix node's decomposed)
  std::vector<glm::mat4> local_matrix;  // per node: its matrix (a TRS node's composed)
  // Per node: its world transform at rest. Read for the nodes of the scene and for every skin's
  // joints and their ancestors (joints may lie outside the scene); identity for other nodes.
  std::vector<glm::mat4> world;
  std::vector<uint32_t> instance_node;  // per Scene instance: the node it came from
  int camera_node = -1;                 // the node Scene::camera came from
  std::vector<uint32_t> light_node;     // per Scene light: the node it is attached to
};
// Instances (one per node with a mesh, depth-first, MSFT_lod levels folded in) and the camera.
NodeTree convert_nodes(const Source& source, Scene& scene);

// glTF skins into Scene::skins, in order, and each instance's skin and morph weights (gltf_skins.cpp).
void convert_skins(const Source& source, const NodeTree& tree, Scene& scene);

// KHR_lights_punctual lights on the nodes of the scene, in node order (gltf_lights.cpp).
void convert_lights(const Source& source, NodeTree& tree, Scene& scene);

// Animation channels into InstanceTrack, LightTrack, JointTrack, MorphTrack and camera keys
// (gltf_animation.cpp).
void convert_animations(const Source& source, const NodeTree& tree, Scene& scene);

// A glTF rotation [x, y, z, w] as a unit quaternion. Rotations already unit length to 1e-3 are
// kept bit for bit (what strata wrote comes back unchanged); others are normalised.
glm::quat read_rotation(const Source& source, double x, double y, double z, double w,
                        const std::string& field);

}  // namespace strata::scene::gltf
