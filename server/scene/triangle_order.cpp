#include "scene/triangle_order.h"

#include <meshoptimizer.h>

namespace strata::scene {

void sort_triangles_spatially(Scene& scene) {
  for (Mesh& mesh : scene.meshes) {
    for (Primitive& p : mesh.primitives) {
      if (p.indices.size() < 6 || p.positions.empty()) continue;
      std::vector<uint32_t> sorted(p.indices.size());
      meshopt_spatialSortTriangles(sorted.data(), p.indices.data(), p.indices.size(), &p.positions[0].x,
                                   p.positions.size(), sizeof(glm::vec3));
      p.indices = std::move(sorted);
    }
  }
}

}  // namespace strata::scene
