// Suffix replay (docs/ARCHITECTURE.md, "Suffix replay") keeps temporal reuse alive when something
// elsewhere in the scene changes: a moving object refuses no shift (a suffix is traced again where
// it is now, or kept where `auto` shows that no change can reach it), and a LoD switch refuses only
// the shifts whose reconnection vertex lies on the switched instance, while `suffix fail` refuses
// every path with a suffix in both cases.
#include <glm/gtc/matrix_transform.hpp>
#include <glm/gtc/quaternion.hpp>

#include "gpu/gpu_context.h"
#include "options/option_table.h"
#include "render/renderer.h"
#include "scene/scene_io.h"
#include "support/test_scenes.h"

namespace strata::test {
namespace {

// Cornell seen from near the back-left corner: neither box is in view; the short box changes
// every frame (it moves, or switches between two LoD levels of the same mesh).
scene::FrameState corner_view(const scene::Scene& s, uint32_t f, bool lod_switch) {
  scene::FrameState st = s.frame_state(0);
  const uint32_t box = instance_named(s, "short_box");
  if (lod_switch) st.lods[box] = f % 2;
  else st.transforms[box] = glm::translate(glm::mat4(1.0f), {0.0f, 0.0f, -0.1f * float(f)}) * st.transforms[box];
  const glm::vec3 eye(0.2f, 1.55f, -0.1f), target(-1.0f, 1.3f, -1.0f);
  st.camera.position = eye;
  st.camera.orientation = glm::normalize(glm::quatLookAtRH(glm::normalize(target - eye), glm::vec3(0.0f, 1.0f, 0.0f)));
  st.camera.yfov = 0.5f;
  return st;
}

struct Totals {
  uint64_t stale = 0, replayed = 0, kept = 0, shifts = 0;
};

Totals run(const scene::Scene& s, const std::string& method, const std::string& suffix, bool lod_switch) {
  render::RenderSettings rs;
  rs.width = 24;
  rs.height = 24;
  rs.method = method;
  rs.max_depth = 5;
  rs.restir.spatial = false;
  strata::options::set_choice(rs.restir, "suffix", suffix);
  render::Renderer renderer(gpu_context(), s, rs);
  Totals t;
  for (uint32_t f = 0; f < 4; ++f) {
    const render::FrameResult r = renderer.render(corner_view(s, f, lod_switch), f);
    auto get = [&](const std::map<std::string, uint64_t>& m, const char* key) {
      auto it = m.find(key);
      return it == m.end() ? uint64_t(0) : it->second;
    };
    t.stale += get(r.stats.shift_failures, "temporal.stale");
    t.replayed += get(r.stats.reuse, "temporal.suffix_replayed");
    t.kept += get(r.stats.reuse, "temporal.suffix_kept");
    t.shifts += get(r.stats.reuse, "temporal.shifts");
  }
  return t;
}

class SuffixReuse : public GpuTest, public ::testing::WithParamInterface<std::string> {};

TEST_P(SuffixReuse, AMovingObjectElsewhereRefusesNoShift) {
  scene::Scene s = scene::builtin_scene("cornell");
  const Totals fail = run(s, GetParam(), "fail", false);
  const Totals automatic = run(s, GetParam(), "auto", false);
  EXPECT_GT(fail.stale, fail.shifts / 10) << "the case must have paths with suffixes";
  EXPECT_EQ(automatic.stale, 0u);
  EXPECT_GT(automatic.replayed + automatic.kept, fail.stale / 2);
  // One-segment suffixes whose ray misses the moving box's swept box keep their radiance; the
  // others, and every longer suffix, are traced again.
  EXPECT_GT(automatic.kept, 0u);
  EXPECT_GT(automatic.replayed, 0u);
  const Totals replay = run(s, GetParam(), "replay", false);
  EXPECT_EQ(replay.kept, 0u) << "suffix replay traces every suffix again once anything changed";
  EXPECT_EQ(replay.replayed, automatic.replayed + automatic.kept);
}

TEST_P(SuffixReuse, ALodSwitchElsewhereRefusesOnlyPathsThatReconnectOnIt) {
  scene::Scene s = scene::builtin_scene("cornell");
  const uint32_t box = instance_named(s, "short_box");
  s.instances[box].lod_meshes.push_back(s.instances[box].lod_meshes[0]);  // level 1: the same mesh
  const Totals fail = run(s, GetParam(), "fail", true);
  const Totals automatic = run(s, GetParam(), "auto", true);
  EXPECT_GT(fail.stale, fail.shifts / 10);
  // Stale now: only x_k on the switched box, which these pixels reach only by a bounce.
  EXPECT_LT(automatic.stale, fail.stale / 10);
  EXPECT_GT(automatic.replayed + automatic.kept, fail.stale / 2);
}

// suffix auto keeps exactly what a replay would find. Frame 0 has the short box on the floor; in
// frame 1 it is a slab under the ceiling light, which blocks the last segment of most paths while
// what the camera sees stays in place. With temporal reuse only, frame 1's image is a continuous
// function of the shifted samples' values (the pixel estimate sums over both candidates), so auto
// and replay agree to rounding wherever auto kept a suffix rightly; a suffix kept although the slab
// crosses it (the swept-box test broken) would show the unshaded light in its pixel.
TEST_P(SuffixReuse, AutoKeepsOnlyWhatAReplayWouldFind) {
  const scene::Scene s = scene::builtin_scene("cornell");
  auto state = [&](uint32_t f) { return f == 1 ? test::cornell_light_shaded(s) : s.frame_state(0); };
  auto render = [&](const std::string& suffix, uint64_t& kept) {
    render::RenderSettings rs;
    rs.width = 32;
    rs.height = 32;
    rs.method = GetParam();
    rs.max_depth = 4;
    rs.restir.spatial = false;
    strata::options::set_choice(rs.restir, "suffix", suffix);
    render::Renderer renderer(gpu_context(), s, rs);
    renderer.render(state(0), 0);
    render::FrameResult r = renderer.render(state(1), 1);
    auto it = r.stats.reuse.find("temporal.suffix_kept");
    kept = it == r.stats.reuse.end() ? 0 : it->second;
    return r.image;
  };
  uint64_t kept_auto = 0, kept_replay = 0;
  const image::Image automatic = render("auto", kept_auto);
  const image::Image replay = render("replay", kept_replay);
  EXPECT_GT(kept_auto, 20u) << "one-segment suffixes clear of the slab and the box's old place";
  EXPECT_EQ(kept_replay, 0u);
  // Tolerance: the kept and the replayed radiance of an untouched suffix differ by float rounding
  // only (render-space positions of two frames); a wrongly kept one differs by the light it claims.
  size_t differing = 0;
  for (size_t i = 0; i < replay.rgba.size(); ++i) {
    if (i % 4 == 3) continue;
    if (std::abs(automatic.rgba[i] - replay.rgba[i]) > 1e-3f * (std::abs(replay.rgba[i]) + 1e-2f)) ++differing;
  }
  EXPECT_EQ(differing, 0u);
}

INSTANTIATE_TEST_SUITE_P(Methods, SuffixReuse, ::testing::Values("restir-gather", "restir-splat"),
                         [](const ::testing::TestParamInfo<std::string>& p) { return method_test_name(p.param); });

}  // namespace
}  // namespace strata::test
