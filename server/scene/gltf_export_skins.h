#pragma once
// The deforming half of export_glb (scene/gltf_export.cpp). Per primitive: JOINTS_0 (unsigned
// short), WEIGHTS_0 (float) and morph targets (POSITION deltas with min/max, NORMAL deltas where
// the target has them). Per skin: a skeleton node, a root of the scene at the identity, whose
// children are the skin's joints, one node each at its rest transform (joint to world), so that
// the joints share a common root as glTF asks (3.7.3.2); `matrix` for a joint without a track,
// else TRS plus its exact rest matrix in extras (gltf_extras.h); the inverse bind matrices as a
// float MAT4 accessor. gltf_export.cpp writes node.skin, node.weights, mesh.weights and the joint
// and morph tracks as animation channels.
#include <string>
#include <vector>

#include "scene/gltf_export_builder.h"

namespace strata::scene::gltf {

// `field` names the primitive in errors ("meshes[0].primitives[1]").
void export_primitive_deformation(GlbBuilder& b, const Primitive& p, const std::string& field,
                                  tinygltf::Primitive& out);

// Appends the skins and their nodes; the skeleton nodes are added to `roots`. Returns per skin the
// node of each joint.
std::vector<std::vector<int>> export_skins(GlbBuilder& b, const Scene& s, std::vector<int>& roots);

}  // namespace strata::scene::gltf
