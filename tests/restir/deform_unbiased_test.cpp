// Skinned and morphing meshes under ReSTIR's shifts (docs/ARCHITECTURE.md, "Deforming meshes"): the
// built-in scene characters, a skinned flag and a morphing blob, stepped 10 animation frames per
// rendered frame so that both deform visibly between consecutive frames (the flag's joints turn by
// up to 0.5 rad, the blob's weights move by up to 0.5), under a still camera and under the scene's
// camera motion. A shift that resolved a stored hit on a deforming instance through the wrong
// frame's vertices would evaluate another surface point than the one its Jacobian is for: checked by
// breaking the code (docs/BENCHMARKS.md, "Characters").
//
// Tolerance: the harness of tests/support/unbiasedness.h, as tests/restir/texture_unbiased_test.cpp
// states it: per 4 x 4 block, the mean over 48 independent runs against a pt reference of 24 runs x
// 64 spp per frame, over frames 1-3; each block's z-score against the Bonferroni threshold for a
// family-wise false-failure probability of 1e-4 over the 16 blocks.
#include <cstdio>
#include <string>
#include <vector>

#include "gpu/gpu_context.h"
#include "render/renderer.h"
#include "restir/sequence_runs.h"
#include "scene/scene_io.h"
#include "support/unbiasedness.h"

namespace strata::test {
namespace {

constexpr uint32_t kStep = 10;  // animation frames per rendered frame

scene::FrameState still_camera(const scene::Scene& s, uint32_t f) {
  scene::FrameState st = s.frame_state(kStep * f);
  st.camera = s.frame_state(0).camera;
  return st;
}

scene::FrameState moving_camera(const scene::Scene& s, uint32_t f) { return s.frame_state(kStep * f); }

struct Case {
  std::string name;
  SequenceRun run;
};

constexpr uint32_t kRuns = 48, kReferenceRuns = 24, kReferenceSpp = 64;

class DeformUnbiased : public GpuTest, public ::testing::WithParamInterface<Case> {};

TEST_P(DeformUnbiased, MatchesPathTracedReference) {
  const Case& c = GetParam();
  const scene::Scene s = scene::builtin_scene("characters");
  expect_matches_pt(s, c.name, c.run, kRuns, kReferenceRuns, kReferenceSpp);
}

std::vector<Case> cases() {
  auto temporal_only = [](render::RestirOptions& o) { o.spatial = false; };
  return {
      {"gather_still_camera", {.method = "restir-gather", .state = still_camera}},
      {"gather_moving_camera", {.method = "restir-gather", .state = moving_camera}},
      {"splat_still_camera", {.method = "restir-splat", .state = still_camera, .options = temporal_only}},
      {"splat_moving_camera", {.method = "restir-splat", .state = moving_camera, .options = temporal_only}},
      {"multilayer_still_camera", {.method = "restir-multilayer", .state = still_camera, .options = temporal_only}},
      {"multilayer_moving_camera", {.method = "restir-multilayer", .state = moving_camera, .options = temporal_only}},
  };
}

INSTANTIATE_TEST_SUITE_P(Cases, DeformUnbiased, ::testing::ValuesIn(cases()),
                         [](const ::testing::TestParamInfo<Case>& p) { return p.param.name; });

}  // namespace
}  // namespace strata::test
