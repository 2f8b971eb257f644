#pragma once
// Triangle order is part of a scene: ray hits, path samples and LoD mappings name triangles by
// index. Loaders and generators put every primitive's triangles in spatial (Morton) order, because
// some BVH builders follow the index order: lavapipe's ray tracing of the `foliage` leaves, whose
// 2,400 triangles were in random order, ran 30x faster once sorted (docs/BENCHMARKS.md).
#include "scene/scene.h"

namespace strata::scene {

// meshopt_spatialSortTriangles on each primitive; idempotent (a stable sort by the same keys), so a
// scene that was already sorted keeps its triangle indices.
void sort_triangles_spatially(Scene& scene);

}  // namespace strata::scene
