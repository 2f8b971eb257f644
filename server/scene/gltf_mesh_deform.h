#pragma once
// Internal to the glTF loader: the attributes that deform a primitive, read for gltf_mesh.cpp.
// Skinning: JOINTS_0 and WEIGHTS_0 (glTF 2.0 3.7.3.3); morph targets and mesh.weights (3.7.2.2).
// Vertices keep the order of the file (the loader never reorders, welds or splits them), so these
// arrays run parallel to Primitive::positions as read.
#include <string>
#include <vector>

#include "scene/gltf_source.h"
#include "scene/scene.h"

namespace strata::scene::gltf {

// JOINTS_0 and WEIGHTS_0 of `p` into out.joints and out.weights (both empty when the primitive has
// neither). Returns the number of vertices whose weights were renormalised (see the .cpp).
size_t read_skin_attributes(const Source& source, const tinygltf::Primitive& p,
                            const std::string& field, size_t vertices, Primitive& out);

// The morph targets of `p` into out.targets. `target_vertices` counts vertices x targets over the
// file, bounded by kMaxMorphTargetVertices.
void read_morph_targets(const Source& source, const tinygltf::Primitive& p, const std::string& field,
                        size_t vertices, size_t& target_vertices, Primitive& out);

// The mesh's default morph weights: mesh.weights, else zeros, one per target. Checks that every
// primitive has the same number of targets, as glTF requires.
std::vector<float> read_mesh_weights(const Source& source, const tinygltf::Mesh& mesh,
                                     const std::string& field, const Mesh& out);

// Vertices x targets over one file: 16 M target vertices hold 384 MiB of deltas.
constexpr size_t kMaxMorphTargetVertices = 16'000'000;

}  // namespace strata::scene::gltf
