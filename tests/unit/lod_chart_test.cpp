// The UV charts that tau (LOD 4.2) maps through: how often each level of a built-in scene's LoD
// groups covers a UV point. lod-cliff's terrain and chess's pieces are laid out so that a point's
// UV names it alone (decimated levels may fold a sliver: at most 1% of points covered twice);
// overlap-uv overlaps on purpose, the mirrored floor twice and the cube's faces six times (LOD
// Fig. 6: where Alg. 1 matching is needed). A chart whose points share UVs with more than
// LOD_MAX_CANDIDATES others fails every mapping as ambiguous (chess's rook did, before its merlons
// got cells of their own).
#include <gtest/gtest.h>

#include <map>
#include <random>

#include "scene/scene_io.h"

namespace strata::scene {
namespace {

float cross2(glm::vec2 a, glm::vec2 b) { return a.x * b.y - a.y * b.x; }

// How many of the primitive's UV triangles contain v.
uint32_t coverage(const Mesh& mesh, glm::vec2 v) {
  uint32_t n = 0;
  for (const Primitive& p : mesh.primitives)
    for (size_t t = 0; t < p.triangle_count(); ++t) {
      const glm::vec2 a = p.uvs[p.indices[3 * t]], b = p.uvs[p.indices[3 * t + 1]], c = p.uvs[p.indices[3 * t + 2]];
      const float d = cross2(b - a, c - a);
      if (std::abs(d) < 1e-12f) continue;
      const float w1 = cross2(v - a, c - a) / d, w2 = cross2(b - a, v - a) / d;
      n += w1 >= 0.0f && w2 >= 0.0f && w1 + w2 <= 1.0f;
    }
  return n;
}

// Per LoD instance and level: the share of sampled UV points (those any triangle covers) that
// exactly `expected` triangles cover.
void expect_coverage(const std::string& scene_name, const std::map<std::string, uint32_t>& expected) {
  const Scene s = builtin_scene(scene_name);
  std::mt19937 rng(7);
  std::uniform_real_distribution<float> uniform(0.0f, 1.0f);
  uint32_t checked = 0;
  for (const Instance& inst : s.instances) {
    if (inst.lod_meshes.size() < 2) continue;
    ASSERT_TRUE(expected.contains(inst.name)) << scene_name << ": " << inst.name;
    for (size_t level = 0; level < inst.lod_meshes.size(); ++level) {
      uint32_t covered = 0, as_expected = 0;
      for (int k = 0; k < 1500; ++k) {
        const uint32_t n = coverage(s.meshes[inst.lod_meshes[level]], {uniform(rng), uniform(rng)});
        covered += n > 0;
        as_expected += n == expected.at(inst.name);
      }
      EXPECT_GT(covered, 1000u) << inst.name << " level " << level << ": its chart fills most of the unit square";
      EXPECT_GE(as_expected, covered * 99 / 100) << scene_name << " " << inst.name << " level " << level;
      ++checked;
    }
  }
  EXPECT_GT(checked, 0u);
}

TEST(LodCharts, LodCliffAndChessGiveEveryPointItsOwnUv) {
  expect_coverage("lod-cliff", {{"terrain", 1}});
  expect_coverage("chess", {{"pawn", 1}, {"queen", 1}, {"rook", 1}});
}

TEST(LodCharts, OverlapUvOverlapsAsDesigned) { expect_coverage("overlap-uv", {{"floor", 2}, {"cube", 6}}); }

}  // namespace
}  // namespace strata::scene
