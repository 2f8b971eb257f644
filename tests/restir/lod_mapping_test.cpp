// LoD-aware reuse (the LOD paper; shaders/include/scene_bridge.glsl, lod_map): what the mapping
// does at a LoD switch, by outcome, and that it stays finite. The image's unbiasedness across
// switches is in restir_unbiased_test.cpp (lod_* cases); the math in tests/unit/lod_mapping_math_test.cpp.
// - overlap-uv (a mirrored floor, a cube whose faces share one UV square): with matching the
//   ambiguous points are matched (LOD Alg. 1), without it they are refused (LOD Fig. 6), and with
//   lod_mapping off every point on the other level is refused;
// - lod-cliff (one UV chart): points map uniquely, and the suffixes of mapped reconnection vertices
//   replay (their direction fixed to the object); chess (lathe seams): nine in ten map or better;
//   the UV structure's memory is reported in its own group and is absent for a scene without LoD
//   groups and for methods without history; the switched pixels keep the spatial boost;
// - numerics: a switch every frame with a teleporting camera, on chess and overlap-uv: all finite.
#include <cmath>
#include <cstdio>
#include <functional>

#include "gpu/gpu_context.h"
#include "render/renderer.h"
#include "scene/scene_io.h"
#include "support/test_scenes.h"

namespace strata::test {
namespace {

struct Outcome {
  std::map<std::string, uint64_t> reuse;  // of the frame with the switch
  std::map<std::string, uint64_t> shift_failures;
  std::map<std::string, uint64_t> memory;
};

render::RenderSettings settings(const std::string& method, uint32_t size) {
  render::RenderSettings rs;
  rs.width = size;
  rs.height = size;
  rs.method = method;
  rs.max_depth = 4;
  return rs;
}

Outcome render_switch(const std::string& scene_name, const std::string& method, std::function<void(render::RestirOptions&)> options) {
  scene::Scene s = scene::builtin_scene(scene_name);
  render::RenderSettings rs = settings(method, 32);
  options(rs.restir);
  render::Renderer renderer(gpu_context(), s, rs);
  Outcome o;
  for (uint32_t f = 0; f < 2; ++f) {
    const render::FrameStats stats = renderer.render(lod_switched(s, 10, f), f).stats;
    o.reuse = stats.reuse;
    o.shift_failures = stats.shift_failures;
  }
  o.memory = renderer.memory_bytes();
  return o;
}

class LodMapping : public GpuTest {};

TEST_F(LodMapping, OverlappingUvsAreMatchedOrRefused) {
  const Outcome matched = render_switch("overlap-uv", "restir-splat", [](render::RestirOptions&) {});
  const Outcome unmatched = render_switch("overlap-uv", "restir-splat", [](render::RestirOptions& o) { o.lod_matching = false; });
  const Outcome off = render_switch("overlap-uv", "restir-splat", [](render::RestirOptions& o) { o.lod_mapping = render::LodMapping::off; });
  std::printf("matching: mappings %llu matched %llu unique %llu ambiguous %llu outside %llu; without: ambiguous %llu; off: refused %llu\n",
              (unsigned long long)matched.reuse.at("lod.mappings"), (unsigned long long)matched.reuse.at("lod.matched"),
              (unsigned long long)matched.reuse.at("lod.unique"), (unsigned long long)matched.reuse.at("lod.failed_ambiguous"),
              (unsigned long long)matched.reuse.at("lod.failed_outside"), (unsigned long long)unmatched.reuse.at("lod.failed_ambiguous"),
              (unsigned long long)off.reuse.at("lod.refused"));
  // Every point of overlap-uv's two LoD groups shares its UV with another point of its level.
  EXPECT_GT(matched.reuse.at("lod.matched"), 0u);
  EXPECT_GT(matched.reuse.at("lod.matched"), 10 * matched.reuse.at("lod.failed_ambiguous"));
  EXPECT_EQ(unmatched.reuse.at("lod.matched"), 0u);
  EXPECT_EQ(unmatched.reuse.at("lod.unique"), 0u);
  EXPECT_GT(unmatched.reuse.at("lod.failed_ambiguous"), 0u);
  EXPECT_GT(unmatched.reuse.at("temporal.shifts"), 0u);
  EXPECT_EQ(off.reuse.at("lod.mappings"), 0u);
  EXPECT_EQ(off.reuse.at("lod.uv_rays"), 0u);
  EXPECT_GT(off.reuse.at("lod.refused"), 0u);
  // Two UV queries per mapping (X_2,v, then X_1,v) unless X_2,v is empty.
  EXPECT_LE(matched.reuse.at("lod.uv_rays"), 2 * matched.reuse.at("lod.mappings"));
  EXPECT_GE(matched.reuse.at("lod.uv_rays"), matched.reuse.at("lod.mappings"));
  EXPECT_GT(matched.memory.at("lod_uv_space"), 0u);
}

TEST_F(LodMapping, OneChartMapsUniquelyAndOnlyLodScenesPayForIt) {
  const Outcome cliff = render_switch("lod-cliff", "restir-splat", [](render::RestirOptions&) {});
  std::printf("lod-cliff: mappings %llu unique %llu outside %llu degenerate %llu\n", (unsigned long long)cliff.reuse.at("lod.mappings"),
              (unsigned long long)cliff.reuse.at("lod.unique"), (unsigned long long)cliff.reuse.at("lod.failed_outside"),
              (unsigned long long)cliff.reuse.at("lod.failed_degenerate"));
  EXPECT_GT(cliff.reuse.at("lod.unique"), 0u);
  EXPECT_EQ(cliff.reuse.at("lod.matched"), 0u);
  EXPECT_GE(cliff.reuse.at("lod.unique"), cliff.reuse.at("lod.mappings") * 99 / 100);
  EXPECT_GT(cliff.memory.at("lod_uv_space"), 0u);

  const Outcome cornell = render_switch("cornell", "restir-splat", [](render::RestirOptions&) {});
  EXPECT_FALSE(cornell.reuse.contains("lod.mappings")) << "a scene without LoD groups reports no LoD statistics";
  EXPECT_FALSE(cornell.memory.contains("lod_uv_space"));
  const Outcome pt = render_switch("lod-cliff", "pt", [](render::RestirOptions&) {});
  EXPECT_FALSE(pt.memory.contains("lod_uv_space")) << "pt keeps no history: nothing to map";
}

// A suffix that leaves a mapped reconnection vertex keeps its direction fixed to the object across
// the switch (path_space.glsl, object_fixed_direction), so on lod-cliff the sun-lit bounces replay
// onto the sun again. Kept in x_k's surface frame instead, the other level's shading normal turns it
// past the 0.6-degree sun, and more than half of the replays failed (docs/BENCHMARKS.md, "Why temporal reuse does not pay on lod-cliff").
TEST_F(LodMapping, SuffixesReplayAcrossTheSwitch) {
  const Outcome cliff = render_switch("lod-cliff", "restir-gather", [](render::RestirOptions&) {});
  const uint64_t replayed = cliff.reuse.at("temporal.suffix_replayed");
  const uint64_t failed = cliff.shift_failures.at("temporal.replay");
  std::printf("lod-cliff restir-gather at the switch: suffixes replayed %llu, replays failed %llu, mappings %llu\n",
              (unsigned long long)replayed, (unsigned long long)failed, (unsigned long long)cliff.reuse.at("lod.mappings"));
  EXPECT_GT(replayed, 0u);
  EXPECT_LT(failed * 10, replayed) << "fewer than one replay in ten fails";
}

// A pixel whose surface switched level keeps the spatial boost of pixels without history
// (disocclusion_spatial_neighbors, restir_spatial.comp) although tau carried its history across:
// lod-cliff's mapped history is worth less than it costs there (docs/BENCHMARKS.md, "The switched pixels keep the spatial boost"). At the
// switch the terrain's pixels then draw 6 neighbours, not 2: with the rule dropped the default run
// equals the run without boost up to the few pixels that have no history at all.
TEST_F(LodMapping, SwitchedPixelsKeepTheSpatialBoost) {
  const Outcome boost = render_switch("lod-cliff", "restir-gather", [](render::RestirOptions&) {});
  const Outcome plain = render_switch("lod-cliff", "restir-gather", [](render::RestirOptions& o) { o.disocclusion_spatial_neighbors = 2; });
  const Outcome off = render_switch("lod-cliff", "restir-gather", [](render::RestirOptions& o) { o.lod_mapping = render::LodMapping::off; });
  std::printf("lod-cliff restir-gather at the switch: spatial shifts %llu (boost 2 -> 2: %llu; lod_mapping off: %llu), mappings %llu\n",
              (unsigned long long)boost.reuse.at("spatial.shifts"), (unsigned long long)plain.reuse.at("spatial.shifts"),
              (unsigned long long)off.reuse.at("spatial.shifts"), (unsigned long long)boost.reuse.at("lod.mappings"));
  EXPECT_GT(boost.reuse.at("lod.mappings"), 0u);
  EXPECT_GT(boost.reuse.at("spatial.shifts"), 2 * plain.reuse.at("spatial.shifts"));
}

// chess: lathed pieces whose charts close on a seam, three levels from make_lod_chain. Both shift
// directions map x_1 at every switch (the restir_unbiased lod_chess_* cases rely on it).
TEST_F(LodMapping, LathedPiecesMapAtEverySwitch) {
  for (const char* method : {"restir-gather", "restir-splat"}) {
    const Outcome chess = render_switch("chess", method, [](render::RestirOptions&) {});
    const uint64_t mapped = chess.reuse.at("lod.unique") + chess.reuse.at("lod.matched");
    std::printf("chess %s: mappings %llu mapped %llu outside %llu ambiguous %llu degenerate %llu\n", method,
                (unsigned long long)chess.reuse.at("lod.mappings"), (unsigned long long)mapped,
                (unsigned long long)chess.reuse.at("lod.failed_outside"), (unsigned long long)chess.reuse.at("lod.failed_ambiguous"),
                (unsigned long long)chess.reuse.at("lod.failed_degenerate"));
    EXPECT_GT(chess.reuse.at("lod.mappings"), 0u) << method;
    EXPECT_GE(mapped, chess.reuse.at("lod.mappings") * 9 / 10) << method;
  }
}

// A LoD switch every frame while the camera jumps between far-apart places (every temporal shift
// disoccluded or grazing), on UV seams (overlap-uv's mirror line, chess's lathe seams).
TEST_F(LodMapping, SwitchEveryFrameWithTeleportingCameraStaysFinite) {
  for (const char* name : {"chess", "overlap-uv"}) {
    for (const char* method : {"restir-splat", "restir-gather"}) {
      SCOPED_TRACE(std::string(name) + " " + method);
      scene::Scene s = scene::builtin_scene(name);
      render::Renderer renderer(gpu_context(), s, settings(method, 24));
      uint64_t mapped = 0;
      for (uint32_t f = 0; f < 4; ++f) {
        scene::FrameState st = lod_switched(s, 10, f);
        if (f % 2 == 1) st.camera.position += glm::vec3(3.0f, 1.0f, -2.0f);
        auto r = renderer.render(st, f);
        for (float v : r.image.rgba) ASSERT_TRUE(std::isfinite(v)) << "frame " << f;
        mapped += r.stats.reuse.at("lod.mappings");
      }
      EXPECT_GT(mapped, 0u);
    }
  }
}

}  // namespace
}  // namespace strata::test
