#pragma once
// Level-of-detail generation with meshoptimizer.
#include <cstdint>
#include <vector>

#include "scene/scene.h"

namespace strata::scene {

// Returns up to `levels` levels (level 0 included). Level 0 is `p` unchanged; level l+1
// simplifies level l towards `ratio` times its triangle count. `lock_border` keeps vertices on
// open mesh borders (terrain edges, open lathe rims) in place, so a coarse level still meets its
// neighbours.
// Simplification only removes vertices, so every output vertex is an input vertex with its
// position, normal and UV bit for bit; vertices are compacted in their original order. Only
// positions guide the collapse: split vertices (UV seams, hard edges) are never welded.
// A level that cannot get smaller than the one before ends the chain early.
std::vector<Primitive> make_lod_chain(const Primitive& p, uint32_t levels, float ratio,
                                      bool lock_border = false);

}  // namespace strata::scene
