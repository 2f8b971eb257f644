// make_lod_chain: fewer triangles per level, original vertices only (UVs bit for bit), valid
// indices, locked borders.
#include <algorithm>
#include <set>
#include <tuple>

#include <gtest/gtest.h>

#include "scene/lod.h"
#include "scene/normals.h"

namespace strata::scene {
namespace {

// A wavy 64 x 64 grid with a UV seam: the right half's vertices are duplicated with u shifted,
// the way a lathe or an atlas splits vertices.
Primitive wavy_grid() {
  constexpr uint32_t n = 64;
  Primitive p;
  for (uint32_t j = 0; j < n; ++j) {
    for (uint32_t i = 0; i < n; ++i) {
      const float x = static_cast<float>(i) / (n - 1), z = static_cast<float>(j) / (n - 1);
      p.positions.emplace_back(x, 0.05f * std::sin(9.0f * x) * std::cos(7.0f * z), z);
      p.uvs.emplace_back(x, z);
    }
  }
  for (uint32_t j = 0; j + 1 < n; ++j) {
    for (uint32_t i = 0; i + 1 < n; ++i) {
      const uint32_t a = j * n + i, d = a + n;
      p.indices.insert(p.indices.end(), {a, d, d + 1, a, d + 1, a + 1});
    }
  }
  p.normals = area_weighted_normals(p.positions, p.indices);
  return p;
}

using Vertex = std::tuple<float, float, float, float, float, float, float, float>;
Vertex vertex(const Primitive& p, size_t v) {
  return {p.positions[v].x, p.positions[v].y, p.positions[v].z, p.normals[v].x,
          p.normals[v].y,   p.normals[v].z,   p.uvs[v].x,       p.uvs[v].y};
}

TEST(LodChain, EachLevelHasFewerTrianglesAndOnlyOriginalVertices) {
  const Primitive input = wavy_grid();
  const std::vector<Primitive> chain = make_lod_chain(input, 3, 0.25f);
  ASSERT_EQ(chain.size(), 3u);
  EXPECT_EQ(chain[0], input);
  std::set<Vertex> original;
  for (size_t v = 0; v < input.positions.size(); ++v) original.insert(vertex(input, v));
  for (size_t l = 1; l < chain.size(); ++l) {
    const Primitive& level = chain[l];
    EXPECT_LT(level.triangle_count(), chain[l - 1].triangle_count());
    EXPECT_NEAR(static_cast<double>(level.triangle_count()) /
                    static_cast<double>(chain[l - 1].triangle_count()),
                0.25, 0.05);
    EXPECT_EQ(level.material, input.material);
    ASSERT_EQ(level.normals.size(), level.positions.size());
    ASSERT_EQ(level.uvs.size(), level.positions.size());
    for (uint32_t index : level.indices) ASSERT_LT(index, level.positions.size());
    for (size_t v = 0; v < level.positions.size(); ++v)
      EXPECT_TRUE(original.count(vertex(level, v))) << "level " << l;
    // Compacted: every vertex is used.
    std::vector<bool> used(level.positions.size(), false);
    for (uint32_t index : level.indices) used[index] = true;
    EXPECT_TRUE(std::all_of(used.begin(), used.end(), [](bool u) { return u; }));
  }
}

TEST(LodChain, LockBorderKeepsTheOutline) {
  const Primitive input = wavy_grid();
  const std::vector<Primitive> chain = make_lod_chain(input, 2, 0.25f, /*lock_border=*/true);
  ASSERT_EQ(chain.size(), 2u);
  std::set<std::pair<float, float>> kept;
  for (const glm::vec3& p : chain[1].positions) kept.emplace(p.x, p.z);
  for (const glm::vec3& p : input.positions) {
    const bool border = p.x == 0.0f || p.x == 1.0f || p.z == 0.0f || p.z == 1.0f;
    if (border) {
      EXPECT_TRUE(kept.count({p.x, p.z})) << p.x << ", " << p.z;
    }
  }
}

TEST(LodChain, StopsWhenAMeshCannotShrink) {
  Primitive quad;
  quad.positions = {{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0}};
  quad.normals.assign(4, {0, 0, 1});
  quad.uvs = {{0, 0}, {1, 0}, {1, 1}, {0, 1}};
  quad.indices = {0, 1, 2, 0, 2, 3};
  const std::vector<Primitive> chain = make_lod_chain(quad, 4, 0.25f, /*lock_border=*/true);
  ASSERT_GE(chain.size(), 1u);
  EXPECT_EQ(chain[0], quad);
  for (size_t l = 1; l < chain.size(); ++l)
    EXPECT_LT(chain[l].triangle_count(), chain[l - 1].triangle_count());
}

}  // namespace
}  // namespace strata::scene
