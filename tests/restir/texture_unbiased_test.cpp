// Textures and alpha-tested materials under ReSTIR's shifts (docs/ARCHITECTURE.md, "The scene
// bridge": the footprint rule): cornell with its white surfaces (floor, ceiling, back wall, boxes)
// under a high-contrast checker base colour texture, so that the primary vertex and the
// reconnection vertex of most paths sit on textured surfaces whose texels differ from pixel to
// pixel; its ceiling light emitting through a checker (a textured emitter, which light sampling
// selects by its integrated texture); and an alpha-masked checker quad under the light that moves
// 10 cm a frame (its transparent texels let light through, its opaque ones cast shadow), so that a
// temporal shift's visibility must apply the alpha test in each frame at the occluder's own
// position. Checked by breaking the code (docs/BENCHMARKS.md): a shift whose primary vertex read
// the base path's texel, or a previous frame's visibility without the alpha test, fails.
//
// Tolerance: the harness of tests/support/unbiasedness.h; per 4 x 4 block, the mean over 48
// independent runs (fixed seeds 1000 + r) against a pt reference of 24 runs x 64 spp per frame
// (fixed seeds 90000 + r), both averaged over frames 1-3; each block's z-score against the
// Bonferroni threshold for a family-wise false-failure probability of 1e-4 over the 16 blocks, and
// the whole image's mean. Sound because the runs are independent and identically distributed, so
// each block's mean is normal to good accuracy (central limit theorem over 48 runs of 16 pixels)
// with a standard error estimated from the runs themselves; an unbiased method fails with
// probability 1e-4 at most, and with fixed seeds a run either always passes or always fails.
#include <cstdio>
#include <functional>
#include <string>
#include <vector>

#include <glm/gtc/matrix_transform.hpp>

#include "gpu/gpu_context.h"
#include "render/renderer.h"
#include "restir/sequence_runs.h"
#include "scene/scene_io.h"
#include "scene/texture_mips.h"
#include "support/test_scenes.h"
#include "support/unbiasedness.h"

namespace strata::test {
namespace {

uint32_t rgba(uint8_t r, uint8_t g, uint8_t b, uint8_t a = 255) {
  return uint32_t(r) | uint32_t(g) << 8 | uint32_t(b) << 16 | uint32_t(a) << 24;
}

// An n x n checker of texels a and b, its sampler nearest in magnification (texel edges stay sharp
// in the image) and trilinear in minification.
int32_t add_checker(scene::Scene& s, uint32_t n, uint32_t a, uint32_t b, scene::ColorSpace space, const std::string& name) {
  image::Rgba8Image img{n, n, {}};
  for (uint32_t y = 0; y < n; ++y)
    for (uint32_t x = 0; x < n; ++x) img.texels.push_back((x + y) % 2 == 0 ? a : b);
  scene::Sampler nearest;
  nearest.mag_filter = scene::TextureFilter::kNearest;
  return scene::add_texture(s.textures, img, space, name, nearest);
}

// cornell, its white material textured, with the alpha-masked occluder as the last instance.
scene::Scene textured_cornell() {
  scene::Scene s = scene::builtin_scene("cornell");
  const int32_t checker = add_checker(s, 8, rgba(255, 255, 255), rgba(50, 50, 50), scene::ColorSpace::kSrgb, "checker");
  for (scene::Material& m : s.materials)
    if (m.name == "white") m.base_color_texture.texture = checker;
  // The ceiling light emits through a 4 x 4 checker of full and a fifth of its emission (linear):
  // next-event estimation selects its two triangles by their integrated texture and each light
  // sample's radiance is the texel it lands on.
  const int32_t glow = add_checker(s, 4, rgba(255, 255, 255), rgba(51, 51, 51), scene::ColorSpace::kLinear, "glow");
  for (scene::Material& m : s.materials)
    if (m.name == "light") m.emissive_texture.texture = glow;
  scene::Material leaf;
  leaf.name = "occluder";
  leaf.base_color = glm::vec3(0.7f);
  leaf.specular = 0.0f;
  leaf.double_sided = true;
  leaf.alpha_mode = scene::AlphaMode::kMask;
  leaf.alpha_cutoff = 0.5f;
  leaf.base_color_texture.texture =
      add_checker(s, 4, rgba(255, 255, 255, 255), rgba(255, 255, 255, 0), scene::ColorSpace::kSrgb, "holes");
  s.materials.push_back(leaf);
  s.meshes.push_back(quad_mesh(0.4f, 0.0f, uint32_t(s.materials.size() - 1)));
  scene::Instance inst;
  inst.name = "occluder";
  inst.lod_meshes = {uint32_t(s.meshes.size() - 1)};
  // Horizontal, 25 cm under the light: the quad's +Z normal turned to +Y.
  inst.transform = glm::rotate(glm::translate(glm::mat4(1.0f), {0.0f, 1.75f, 0.0f}), glm::radians(-90.0f), glm::vec3(1, 0, 0));
  s.instances.push_back(inst);
  s.validate();
  return s;
}

// The occluder 5 cm left of its place in even frames, 5 cm right in odd ones: 10 cm a frame, half
// of one of its 20 cm texels, so that a shadow ray of a temporal shift meets a hole in one frame
// where it meets an opaque texel in the other.
scene::FrameState moving_occluder(const scene::Scene& s, uint32_t f) {
  scene::FrameState st = s.frame_state(0);
  const float x = (f % 2 == 0) ? -0.05f : 0.05f;
  st.transforms.back() = glm::translate(glm::mat4(1.0f), {x, 0.0f, 0.0f}) * st.transforms.back();
  return st;
}

struct Case {
  std::string name;
  SequenceRun run;
};

constexpr uint32_t kRuns = 48, kReferenceRuns = 24, kReferenceSpp = 64;

class TextureUnbiased : public GpuTest, public ::testing::WithParamInterface<Case> {};

TEST_P(TextureUnbiased, MatchesPathTracedReference) {
  const Case& c = GetParam();
  const scene::Scene s = textured_cornell();
  expect_matches_pt(s, c.name, c.run, kRuns, kReferenceRuns, kReferenceSpp);
}

std::vector<Case> cases() {
  auto temporal_only = [](render::RestirOptions& o) { o.spatial = false; };
  return {
      {"gather_textured_moving_alpha", {.method = "restir-gather", .state = moving_occluder}},
      {"splat_textured_moving_alpha", {.method = "restir-splat", .state = moving_occluder, .options = temporal_only}},
  };
}

INSTANTIATE_TEST_SUITE_P(Cases, TextureUnbiased, ::testing::ValuesIn(cases()),
                         [](const ::testing::TestParamInfo<Case>& p) { return p.param.name; });

}  // namespace
}  // namespace strata::test
