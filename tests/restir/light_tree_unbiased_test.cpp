// The light tree (render/light_tree.h, light_sampler tree) keeps every estimate unbiased: pt's, and
// every ReSTIR method's whose shifts evaluate light probabilities in the previous frame with that
// frame's tree, while lamps and an emitter move (each frame's tree differs from the one before).
// The Cornell box with its ceiling emitter moving and ten lamps, one of them moving; harness of
// tests/support/unbiasedness.h against converged pt references that choose lights by power.
#include <cstdio>
#include <string>
#include <vector>

#include <glm/gtc/matrix_transform.hpp>

#include "gpu/gpu_context.h"
#include "restir/sequence_runs.h"
#include "scene/scene_io.h"
#include "support/unbiasedness.h"

namespace strata::test {
namespace {

constexpr uint32_t kRuns = 64, kReferenceRuns = 24, kReferenceSpp = 64;

scene::Light lamp(scene::LightType type, float intensity, glm::vec3 position) {
  scene::Light l;
  l.name = "lamp";
  l.type = type;
  l.intensity = intensity;
  l.outer_cone = glm::radians(50.0f);
  // Local -Z (where a spot shines) points down.
  l.transform = glm::translate(glm::mat4(1.0f), position) * glm::rotate(glm::mat4(1.0f), glm::radians(-90.0f), glm::vec3(1, 0, 0));
  return l;
}

// Cornell with ten lamps of different power along the walls (points and spots), so that the tree's
// choice at a point differs much from power's.
scene::Scene lamps_cornell() {
  scene::Scene s = scene::builtin_scene("cornell");
  for (int k = 0; k < 10; ++k) {
    const float x = -0.8f + 0.18f * float(k), z = (k % 2 ? -0.7f : 0.6f);
    s.lights.push_back(lamp(k % 3 == 0 ? scene::LightType::kSpot : scene::LightType::kPoint, 0.1f + 0.15f * float(k % 4),
                            {x, 0.4f + 0.13f * float(k), z}));
  }
  s.validate();
  return s;
}

// The ceiling light (instance "light") slides 10 cm along x and back, lamp 0 40 cm along z.
scene::FrameState moving_lights(const scene::Scene& s, uint32_t f) {
  scene::FrameState st = s.frame_state(0);
  const float sign = f % 2 == 0 ? -1.0f : 1.0f;
  for (size_t i = 0; i < s.instances.size(); ++i)
    if (s.instances[i].name == "light") st.transforms[i] = glm::translate(glm::mat4(1.0f), {0.1f * sign, 0.0f, 0.0f}) * st.transforms[i];
  st.lights[0] = glm::translate(glm::mat4(1.0f), {0.0f, 0.0f, 0.2f * sign}) * st.lights[0];
  return st;
}

struct Case {
  std::string name;
  SequenceRun run;
};

class LightTreeUnbiased : public GpuTest, public ::testing::WithParamInterface<Case> {};

TEST_P(LightTreeUnbiased, MatchesPathTracedReference) {
  const Case& c = GetParam();
  expect_matches_pt(lamps_cornell(), c.name, c.run, kRuns, kReferenceRuns, kReferenceSpp);
}

std::vector<Case> cases() {
  auto tree = [](render::RestirOptions& o) { o.light_sampler = render::LightSampler::tree; };
  auto tree_temporal = [](render::RestirOptions& o) {
    o.light_sampler = render::LightSampler::tree;
    o.spatial = false;
  };
  std::vector<Case> v;
  v.push_back({"pt_moving", {.method = "pt", .state = moving_lights, .options = tree}});
  v.push_back({"di_moving", {.method = "restir-di", .max_depth = 2, .state = moving_lights, .options = tree_temporal}});
  v.push_back({"gather_moving", {.method = "restir-gather", .state = moving_lights, .options = tree}});
  v.push_back({"gather_still", {.method = "restir-gather", .options = tree_temporal}});  // stored suffixes kept
  v.push_back({"splat_moving", {.method = "restir-splat", .state = moving_lights, .options = tree_temporal}});
  return v;
}

INSTANTIATE_TEST_SUITE_P(Cases, LightTreeUnbiased, ::testing::ValuesIn(cases()),
                         [](const ::testing::TestParamInfo<Case>& p) { return p.param.name; });

}  // namespace
}  // namespace strata::test
