#include "scene/lod.h"

#include <limits>

#include <meshoptimizer.h>

namespace strata::scene {
namespace {

// Keeps only the vertices `indices` uses, in their original order, and renumbers `indices`.
Primitive compact(const Primitive& source, std::vector<uint32_t> indices) {
  constexpr uint32_t kUnused = std::numeric_limits<uint32_t>::max();
  std::vector<uint32_t> remap(source.positions.size(), kUnused);
  for (uint32_t index : indices) remap[index] = 0;
  Primitive out;
  out.material = source.material;
  for (size_t v = 0; v < remap.size(); ++v) {
    if (remap[v] == kUnused) continue;
    remap[v] = static_cast<uint32_t>(out.positions.size());
    out.positions.push_back(source.positions[v]);
    out.normals.push_back(source.normals[v]);
    out.uvs.push_back(source.uvs[v]);
    if (!source.uvs1.empty()) out.uvs1.push_back(source.uvs1[v]);
    if (!source.tangents.empty()) out.tangents.push_back(source.tangents[v]);
  }
  for (uint32_t& index : indices) index = remap[index];
  out.indices = std::move(indices);
  return out;
}

Primitive simplify(const Primitive& source, float ratio, bool lock_border) {
  const size_t target =
      static_cast<size_t>(static_cast<double>(source.indices.size() / 3) * ratio) * 3;
  std::vector<uint32_t> indices(source.indices.size());
  // target_error 1.0 (the whole mesh extent) lets the triangle target decide how far to go.
  const size_t count = meshopt_simplify(
      indices.data(), source.indices.data(), source.indices.size(), &source.positions[0].x,
      source.positions.size(), sizeof(glm::vec3), target, 1.0f,
      lock_border ? static_cast<unsigned>(meshopt_SimplifyLockBorder) : 0u, nullptr);
  indices.resize(count);
  return compact(source, std::move(indices));
}

}  // namespace

std::vector<Primitive> make_lod_chain(const Primitive& p, uint32_t levels, float ratio,
                                      bool lock_border) {
  std::vector<Primitive> chain{p};
  while (chain.size() < levels && !chain.back().indices.empty()) {
    Primitive next = simplify(chain.back(), ratio, lock_border);
    if (next.triangle_count() >= chain.back().triangle_count() || next.indices.empty()) break;
    chain.push_back(std::move(next));
  }
  return chain;
}

}  // namespace strata::scene
