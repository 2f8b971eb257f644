#pragma once
// Vertex normals for meshes that come without them.
#include <cstdint>
#include <span>
#include <vector>

#include <glm/glm.hpp>

namespace strata::scene {

// Area-weighted average of the face normals around each vertex (vertices are not welded, so
// hard edges and UV seams stay as the mesh has them). A vertex used only by zero-area triangles,
// or by none, gets +Y. `indices` must be in range and a multiple of 3.
std::vector<glm::vec3> area_weighted_normals(std::span<const glm::vec3> positions,
                                             std::span<const uint32_t> indices);

}  // namespace strata::scene
