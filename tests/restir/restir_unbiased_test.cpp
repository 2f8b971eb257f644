// Unbiasedness of restir-gather and restir-di with the harness of tests/support:
// the per-pixel mean over R independent sequences (fresh seeds, F frames each; a sequence's value is
// the mean of its frames 1..F-1, all of which reuse history) must match a converged `pt` reference
// of the same frame states. The test per 4x4 block is a two-sided z-test at the Bonferroni threshold
// for a family-wise false-failure probability of 1e-4 (sound: sequences are independent and
// identically distributed, so their block means are normal to good accuracy for R >= 24; the
// reference's own standard error enters the z-score), plus a z-test of the image mean.
// It fails when the math is broken: see docs/BENCHMARKS.md "Checked by breaking the code".
// The reference is as fine as the test needs and no finer: its share of each z-score's variance
// (printed as "reference's variance share") is 1-18%, mostly about 5%, with the spp below. At 8x
// the spp it was 0.05-3%, and the references took two thirds of the suite's time for z-scores
// 1-9% sharper.
#include <cstdio>
#include <deque>
#include <functional>
#include <stdexcept>
#include <utility>
#include <vector>

#include <glm/gtc/matrix_transform.hpp>
#include <glm/gtc/quaternion.hpp>

#include "gpu/gpu_context.h"
#include "options/option_table.h"
#include "render/renderer.h"
#include "scene/scene_io.h"
#include "scene/shutter.h"
#include "support/test_scenes.h"
#include "support/unbiasedness.h"

namespace strata::test {
namespace {


struct Case {
  std::string name;
  std::string scene;
  std::string method = "restir-gather";
  uint32_t max_depth = 6;
  uint32_t frames = 4;
  uint32_t runs = 96;
  uint32_t size = 16;  // image width and height
  uint32_t reference_runs = 32;
  uint32_t reference_spp = 64;
  std::function<void(render::RestirOptions&)> options = [](render::RestirOptions&) {};
  // The frames a sequence's value averages (default 1 .. F-1: all that reuse history).
  std::function<bool(uint32_t)> scored = [](uint32_t f) { return f >= 1; };
  // Frame state of frame f (default: the scene's animation).
  std::function<scene::FrameState(const scene::Scene&, uint32_t)> state = [](const scene::Scene& s, uint32_t f) {
    return s.frame_state(f);
  };
  bool expect_bias = false;  // a biased variant the test must detect (the cases' power)
  // The per-pixel statistic tested (RunningImage): r + g + b, or a chromatic one for the colour cases.
  glm::vec3 channels = glm::vec3(1.0f);
  // A change to the built-in scene, and its name (part of the reference's key); "built": the edit
  // builds the whole scene (test_scenes.h) and `scene` names it.
  std::string variant;
  std::function<void(scene::Scene&)> edit = [](scene::Scene&) {};
};

scene::Scene case_scene(const Case& c) {
  scene::Scene s = c.variant == "built" ? scene::Scene{} : scene::builtin_scene(c.scene);
  c.edit(s);
  return s;
}

uint32_t scored_frames(const Case& c) {
  uint32_t n = 0;
  for (uint32_t f = 0; f < c.frames; ++f) n += c.scored(f);
  return n;
}

// Mean over the scored frames of one sequence.
image::Image sequence_mean(const scene::Scene& s, const Case& c, uint32_t seed) {
  render::RenderSettings rs;
  rs.width = c.size;
  rs.height = c.size;
  rs.method = c.method;
  rs.max_depth = c.max_depth;
  rs.seed = seed;
  c.options(rs.restir);
  render::Renderer renderer(gpu_context(), s, rs);
  image::Image mean;
  for (uint32_t f = 0; f < c.frames; ++f) {
    auto r = renderer.render(c.state(s, f), f);
    for (float v : r.image.rgba) EXPECT_TRUE(std::isfinite(v)) << c.name << " frame " << f;
    if (!c.scored(f)) continue;
    if (mean.rgba.empty()) mean = r.image;
    else
      for (size_t i = 0; i < mean.rgba.size(); ++i) mean.rgba[i] += r.image.rgba[i];
  }
  for (float& v : mean.rgba) v /= float(scored_frames(c));
  return mean;
}

RunningImage render_reference(const scene::Scene& s, const Case& c, uint32_t runs, uint32_t spp) {
  RunningImage out(c.size, c.size, c.channels);
  for (uint32_t r = 0; r < runs; ++r) {
    render::RenderSettings rs;
    rs.width = c.size;
    rs.height = c.size;
    rs.spp = spp;
    rs.max_depth = c.max_depth;
    rs.seed = 90000 + r;
    image::Image mean;
    for (uint32_t f = 1; f < c.frames; ++f) {
      if (!c.scored(f)) continue;
      render::Renderer renderer(gpu_context(), s, rs);
      auto img = renderer.render(c.state(s, f), f).image;
      if (mean.rgba.empty()) mean = img;
      else
        for (size_t i = 0; i < mean.rgba.size(); ++i) mean.rgba[i] += img.rgba[i];
    }
    for (float& v : mean.rgba) v /= float(scored_frames(c));
    out.add(mean);
  }
  return out;
}

// What a reference depends on: the scene, the depth, its size and the scored frames' states. Cases that
// agree on it (most cornell cases, the carousel cases, each motion) share one render: the
// reference's seeds are fixed, so a shared reference is the very image each would render.
struct ReferenceKey {
  std::string scene;  // name and variant
  uint32_t max_depth, size, runs, spp;
  glm::vec3 channels;
  std::vector<std::pair<uint32_t, scene::FrameState>> scored;
  bool operator==(const ReferenceKey&) const = default;
};

const RunningImage& reference_of(const scene::Scene& s, const Case& c, uint32_t runs, uint32_t spp) {
  static std::deque<std::pair<ReferenceKey, RunningImage>> cache;  // stable references
  ReferenceKey key{c.scene + "/" + c.variant, c.max_depth, c.size, runs, spp, c.channels, {}};
  for (uint32_t f = 1; f < c.frames; ++f)
    if (c.scored(f)) key.scored.emplace_back(f, c.state(s, f));
  for (const auto& [k, image] : cache)
    if (k == key) return image;
  cache.emplace_back(std::move(key), render_reference(s, c, runs, spp));
  return cache.back().second;
}

class RestirUnbiased : public GpuTest, public ::testing::WithParamInterface<Case> {};

TEST_P(RestirUnbiased, MatchesPathTracedReference) {
  const Case& c = GetParam();
  scene::Scene s = case_scene(c);
  const RunningImage& reference = reference_of(s, c, c.reference_runs, c.reference_spp);
  RunningImage method(c.size, c.size, c.channels);
  for (uint32_t r = 0; r < c.runs; ++r) method.add(sequence_mean(s, c, 1000 + r));
  BiasReport report = compare_to_reference(method, reference, 4);
  std::printf("%s: %s\n", c.name.c_str(), report.describe().c_str());
  if (c.expect_bias) EXPECT_FALSE(report.passed) << c.name << " should be detected as biased: " << report.describe();
  else EXPECT_TRUE(report.passed) << c.name << ": " << report.describe();
}

// The settings of the spatial_filter_* cases do refuse neighbours: the filter is exercised.
class SpatialFilter : public GpuTest {};

TEST_F(SpatialFilter, RefusesCandidatesAcrossSurfaces) {
  for (const char* name : {"cornell", "carousel"}) {
    scene::Scene s = scene::builtin_scene(name);
    render::RenderSettings rs;
    rs.width = 16;
    rs.height = 16;
    rs.method = "restir-gather";
    rs.max_depth = 6;
    rs.restir.temporal = false;
    rs.restir.spatial_neighbors = 3;
    rs.restir.spatial_radius = 6.0f;
    render::Renderer renderer(gpu_context(), s, rs);
    auto r = renderer.render(s.frame_state(0), 0);
    const auto& reuse = r.stats.reuse;
    ASSERT_TRUE(reuse.contains("spatial.filtered")) << name;
    EXPECT_GT(reuse.at("spatial.filtered"), 0u) << name;
    EXPECT_GT(reuse.at("spatial.shifts"), 0u) << name << ": the filter must leave neighbours to reuse";
    std::printf("%s: spatial.filtered %llu, spatial.shifts %llu\n", name, (unsigned long long)reuse.at("spatial.filtered"),
                (unsigned long long)reuse.at("spatial.shifts"));
  }
}

// A camera that moves sideways and forward each frame (cornell's default camera).
scene::FrameState moving_camera(const scene::Scene& s, uint32_t f) {
  scene::FrameState st = s.frame_state(0);
  st.camera.position += glm::vec3(0.04f * float(f), 0.02f * float(f), -0.05f * float(f));
  return st;
}

// Forward motion only: the image magnifies, so splats spread out and leave holes (RS-main 4.2).
scene::FrameState forward_camera(const scene::Scene& s, uint32_t f) {
  scene::FrameState st = s.frame_state(0);
  st.camera.position += glm::vec3(0.0f, 0.0f, -0.25f * float(f));
  return st;
}

// Depth of field (RS-main 4.5): cornell's camera with a 40 cm thin lens focused 2.5 m away (well
// in front of the back wall, so most of the image is strongly defocused), moving as in
// moving_camera; the lens sample is kept in the reservoir and splats project through it.
scene::FrameState dof_camera(const scene::Scene& s, uint32_t f) {
  scene::FrameState st = moving_camera(s, f);
  st.camera.aperture = 0.4f;
  st.camera.focus_distance = 2.5f;
  return st;
}

// Motion blur (RS-main 4.4): cornell's camera turning 4 degrees, sliding 8 cm and zooming in per
// frame, with the shutter open for 3/4 of the frame interval: the reference path-traces each frame
// over the same shutter (time uniform, camera interpolated as GpuShutter says).
scene::Camera blur_camera_at(const scene::Scene& s, float f) {
  scene::Camera c = s.frame_state(0).camera;
  c.position += glm::vec3(0.08f * f, 0.0f, -0.03f * f);
  c.orientation = glm::angleAxis(glm::radians(4.0f) * f, glm::vec3(0, 1, 0)) * c.orientation;
  c.yfov -= 0.02f * f;
  c.shutter = 0.75f;
  return c;
}

scene::FrameState blur_camera(const scene::Scene& s, uint32_t f) {
  scene::FrameState st = s.frame_state(0);
  st.camera = blur_camera_at(s, float(f));
  st.camera_open = scene::shutter_open_camera(blur_camera_at(s, float(f) - 1.0f), st.camera);
  return st;
}

// Suffix replay (restir/suffix_replay.glsl): cornell with one instance jumping between two places
// every frame, so that what a path's suffix after its reconnection vertex sees differs between
// any two frames: a stored suffix radiance is always the other configuration's (cached is biased).
scene::FrameState jumping(const scene::Scene& s, uint32_t f, const std::string& name, glm::vec3 offset) {
  scene::FrameState st = s.frame_state(0);
  const uint32_t i = instance_named(s, name);
  if (f % 2 == 1) st.transforms[i] = glm::translate(glm::mat4(1.0f), offset) * st.transforms[i];
  return st;
}

// The tall box jumps up under the ceiling light (its top 30 cm below it) and back: every other
// frame it shadows most of the room, so the light arriving at reconnection vertices changes everywhere.
scene::FrameState moving_occluder(const scene::Scene& s, uint32_t f) { return jumping(s, f, "tall_box", {0.35f, 0.5f, 0.35f}); }

// The ceiling light moves 0.8 m towards the red wall and back: every NEE end moves with it.
scene::FrameState moving_emitter(const scene::Scene& s, uint32_t f) { return jumping(s, f, "light", {-0.7f, 0.0f, 0.4f}); }

// The short box flattened into a slab under the ceiling light every other frame
// (test::cornell_light_shaded), so a one-segment suffix kept from the other frame is wrong almost
// everywhere. The light that leaks through the 2 cm gap gives heavy tails: at 64 runs even the
// initial candidates alone reached a block |z| of 7.5, at 256 runs 2.6.
scene::FrameState light_shade(const scene::Scene& s, uint32_t f) {
  return f % 2 == 1 ? test::cornell_light_shaded(s) : s.frame_state(0);
}

// The tall box made of rough metal (GGX alpha 0.25, rough enough to reconnect on): a replayed
// suffix that bounces off it samples its direction there from the same random numbers but from
// another incoming direction once the box has moved, so the density of the replayed direction
// changes and the replay Jacobian's suffix_density(x) / suffix_density(y) matters.
void glossy_tall_box(scene::Scene& s) {
  scene::Material m;
  m.name = "glossy";
  m.base_color = glm::vec3(0.9f, 0.8f, 0.6f);
  m.metallic = 1.0f;
  m.roughness = 0.5f;
  s.materials.push_back(m);
  for (scene::Mesh& mesh : s.meshes)
    if (mesh.name == "tall_box")
      for (scene::Primitive& p : mesh.primitives) p.material = uint32_t(s.materials.size() - 1);
}

// The camera at `eye` looking at cornell's back-left corner (y up), with vertical field of view `yfov`.
void aim_at_corner(scene::FrameState& st, glm::vec3 eye, float yfov) {
  const glm::vec3 target(-1.0f, 1.3f, -1.0f);
  st.camera.position = eye;
  st.camera.orientation = glm::normalize(glm::quatLookAtRH(glm::normalize(target - eye), glm::vec3(0.0f, 1.0f, 0.0f)));
  st.camera.yfov = yfov;
}

// A camera close to the back-left corner that sees neither box; the tall box moves in front of the
// red wall it sees, so the box changes these pixels only through paths that bounce off a seen surface.
scene::FrameState suffix_only_motion(const scene::Scene& s, uint32_t f) {
  scene::FrameState st = jumping(s, f, "tall_box", {-0.35f, 0.0f, 0.8f});
  aim_at_corner(st, {0.2f, 1.55f, -0.1f}, 0.5f);
  return st;
}

// The room's back-left corner seen from 1.5 m through a wide lens focused 40 cm away, temporal
// reuse only: a pixel's primary vertices of two frames (two lens samples) lie up to a metre apart
// on the walls beside the corner, about as far as their reconnection vertices on the other wall,
// so the temporal shift's Jacobian (reconnection.h) ranges far from 1. The lens is what makes the
// case see a temporal J = 1 (|z| 12.3); through a pinhole it does not (0.2): docs/BENCHMARKS.md.
scene::FrameState dof_corner(const scene::Scene& s, uint32_t f) {
  scene::FrameState st = s.frame_state(0);
  aim_at_corner(st, {0.2f + 0.03f * float(f), 1.55f, -0.1f}, 0.9f);
  st.camera.aperture = 0.3f;
  st.camera.focus_distance = 0.4f;
  return st;
}

// test::two_planes with its front quad jumping 60 cm sideways every frame: the back plane it
// uncovers was hidden one frame and visible the frame before (ML's disocclusion trail).
void two_planes_scene(scene::Scene& s) { s = two_planes(0.5f, 0.5f); }
scene::FrameState front_jumping(const scene::Scene& s, uint32_t f) {
  scene::FrameState st = s.frame_state(0);
  st.transforms[instance_named(s, "front")] = glm::translate(glm::mat4(1.0f), {f % 2 == 0 ? -0.3f : 0.3f, 0.0f, 0.0f});
  return st;
}

std::vector<Case> cases() {
  std::vector<Case> v;
  v.push_back({.name = "initial_only", .scene = "cornell", .options = [](render::RestirOptions& o) {
                 o.temporal = false;
                 o.spatial = false;
               }});
  v.push_back({.name = "static_hybrid_pairwise", .scene = "cornell"});
  v.push_back({.name = "moving_camera", .scene = "cornell", .state = moving_camera});
  // Gather under forward motion (the splat methods have their case below): the camera dollies
  // 25 cm per frame, so the image magnifies and pixels at the edges lose their history.
  v.push_back({.name = "gather_forward_motion", .scene = "cornell", .options = [](render::RestirOptions& o) { o.spatial = false; },
               .state = forward_camera});
  v.push_back({.name = "gather_dof_corner", .scene = "cornell", .options = [](render::RestirOptions& o) { o.spatial = false; },
               .state = dof_corner});
  v.push_back({.name = "reconnection_shift", .scene = "cornell", .options = [](render::RestirOptions& o) { o.shift = render::Shift::reconnection; }});
  v.push_back({.name = "balance_mis_3_neighbours", .scene = "cornell", .options = [](render::RestirOptions& o) {
                 o.mis = render::Mis::balance;
                 o.spatial_neighbors = 3;
                 o.spatial_radius = 6.0f;
               }});
  v.push_back({.name = "pairwise_mis_3_neighbours", .scene = "cornell", .options = [](render::RestirOptions& o) {
                 o.spatial_neighbors = 3;
                 o.spatial_radius = 6.0f;
               }});
  v.push_back({.name = "carousel_moving_glossy", .scene = "carousel"});
  // The spatial neighbour filter (pixel-centre normal, depth and material kind from the visibility
  // buffer; restir_spatial.comp) with spatial reuse alone, so the filtered neighbours are the only
  // reuse: 3 neighbours of up to 4 tries each in a radius that spans the boxes' edges and the
  // walls' corners (cornell) and the glossy and metal objects (carousel). Unbiased because the
  // filter reads geometry only; docs/BENCHMARKS.md's break check filters on the neighbour's p-hat.
  auto filtered_spatial_only = [](render::RestirOptions& o) {
    o.temporal = false;
    o.spatial_neighbors = 3;
    o.spatial_radius = 6.0f;
  };
  v.push_back({.name = "spatial_filter_cornell", .scene = "cornell", .options = filtered_spatial_only});
  v.push_back({.name = "spatial_filter_carousel", .scene = "carousel", .options = filtered_spatial_only});
  // The colour control variate at full weight (b = 1 everywhere, no shrinkage), scored on r - g:
  // the variate keeps each pixel's luminance, so a bias of it (a w or b that depends on the pixel's
  // own paths; docs/BENCHMARKS.md, its break checks) is in the colour, which cornell's red and green
  // walls give to every surface.
  auto colour_cv_full = [](render::RestirOptions& o) {
    o.colour_cv = 1.0f;
    o.colour_cv_spread = 0.0f;
  };
  const glm::vec3 red_minus_green(1.0f, -1.0f, 0.0f);
  v.push_back({.name = "colour_cv_full_gather", .scene = "cornell", .options = colour_cv_full, .state = moving_camera,
               .channels = red_minus_green});
  v.push_back({.name = "colour_cv_full_splat", .scene = "cornell", .method = "restir-splat", .options = colour_cv_full,
               .state = moving_camera, .channels = red_minus_green});
  v.push_back({.name = "di_mode", .scene = "cornell", .method = "restir-di", .max_depth = 2,
               .options = [](render::RestirOptions& o) { o.light_candidates = 4; }});
  // restir-splat: the temporal reuse alone (spatial off) under each kind of motion, and
  // with the default spatial reuse on the moving, glossy carousel.
  auto splat_only = [](render::RestirOptions& o) { o.spatial = false; };
  v.push_back({.name = "splat_static", .scene = "cornell", .method = "restir-splat", .options = splat_only});
  v.push_back({.name = "splat_moving_camera", .scene = "cornell", .method = "restir-splat", .options = splat_only, .state = moving_camera});
  v.push_back({.name = "splat_forward_motion", .scene = "cornell", .method = "restir-splat", .options = splat_only, .state = forward_camera});
  v.push_back({.name = "splat_carousel", .scene = "carousel", .method = "restir-splat"});
  // The ML paper's "more initial spp" disocclusion baseline: 4 candidates where no splat landed.
  v.push_back({.name = "splat_forward_motion_boost", .scene = "cornell", .method = "restir-splat", .options = [](render::RestirOptions& o) {
                 o.spatial = false;
                 o.disocclusion_initial_candidates = 4;
               }, .state = forward_camera});
  v.push_back({.name = "splat_depth_of_field", .scene = "cornell", .method = "restir-splat", .options = splat_only, .state = dof_camera});
  // restir-splat-backup: the backup sample and the MIS of RS-supp Eq. 20-22.
  v.push_back({.name = "splat_backup_moving_camera", .scene = "cornell", .method = "restir-splat-backup", .options = splat_only,
               .state = moving_camera});
  v.push_back({.name = "splat_backup_forward_motion", .scene = "cornell", .method = "restir-splat-backup", .options = splat_only,
               .state = forward_camera});
  v.push_back({.name = "splat_backup_carousel", .scene = "carousel", .method = "restir-splat-backup", .options = splat_only});
  // Motion blur: the naive backprojected extension (restir-gather, RS-main 4.4.1), splatting with
  // the time offset kept (Eq. 18) and multi-splatting into K partitions (Eq. 19), with the backup.
  v.push_back({.name = "gather_motion_blur", .scene = "cornell", .state = blur_camera});
  v.push_back({.name = "splat_motion_blur", .scene = "cornell", .method = "restir-splat", .options = splat_only, .state = blur_camera});
  v.push_back({.name = "splat_multi_motion_blur", .scene = "cornell", .method = "restir-splat",
               .options = [](render::RestirOptions& o) {
                 o.spatial = false;
                 o.splats_per_frame = 3;
               },
               .state = blur_camera});
  v.push_back({.name = "splat_backup_multi_motion_blur", .scene = "cornell", .method = "restir-splat-backup",
               .options = [](render::RestirOptions& o) {
                 o.spatial = false;
                 o.splats_per_frame = 2;
               },
               .state = blur_camera});
  // Suffix replay under scene changes, for gather and splat (temporal reuse only: the shifts under test).
  for (const auto& [name, state] : std::vector<std::pair<std::string, decltype(Case::state)>>{
           {"moving_occluder", moving_occluder}, {"moving_emitter", moving_emitter}, {"suffix_only_motion", suffix_only_motion}}) {
    // Scored where the instance is away (odd frames): the bias of a stored suffix (the other
    // configuration's light) then has one sign in every scored frame instead of cancelling.
    v.push_back({.name = "replay_" + name, .scene = "cornell", .frames = 6, .runs = 64, .options = [](render::RestirOptions& o) {
                   o.spatial = false;
                   o.suffix = render::Suffix::replay;
                 }, .scored = [](uint32_t f) { return f % 2 == 1; }, .state = state});
  }
  // suffix auto keeps a one-segment suffix whose ray misses the swept boxes of the changed
  // instances: where the jumping box meets a suffix (it shadows most of the room every other
  // frame) that suffix must be traced again, and the others give the replay's value unchanged
  // (tests/restir/suffix_reuse_test.cpp compares the two modes' images directly).
  for (const auto& [name, state] : std::vector<std::pair<std::string, decltype(Case::state)>>{
           {"moving_occluder", moving_occluder}, {"suffix_only_motion", suffix_only_motion}}) {
    v.push_back({.name = "auto_" + name, .scene = "cornell", .frames = 6, .runs = 64, .options = [](render::RestirOptions& o) {
                   o.spatial = false;
                   o.suffix = render::Suffix::automatic;
                 }, .scored = [](uint32_t f) { return f % 2 == 1; }, .state = state});
  }
  // ... and where the slab shades the light: keeping a suffix the slab crosses is caught here
  // (the swept-box test switched off: block |z| 12.9; `cached`: 19.5).
  v.push_back({.name = "auto_light_shade", .scene = "cornell", .frames = 6, .runs = 256, .options = [](render::RestirOptions& o) {
                 o.spatial = false;
                 o.suffix = render::Suffix::automatic;
               }, .scored = [](uint32_t f) { return f % 2 == 1; }, .state = light_shade});
  v.push_back({.name = "replay_glossy_moving_occluder", .scene = "cornell", .frames = 6, .runs = 64,
               .options = [](render::RestirOptions& o) {
                 o.spatial = false;
                 o.suffix = render::Suffix::replay;
               },
               .scored = [](uint32_t f) { return f % 2 == 1; }, .state = moving_occluder, .variant = "glossy_tall_box",
               .edit = glossy_tall_box});
  // The cases are strong enough to see the stored suffix's bias (the references' `cached`).
  v.push_back({.name = "cached_moving_emitter_is_biased", .scene = "cornell", .frames = 6, .runs = 64,
               .options = [](render::RestirOptions& o) {
                 o.spatial = false;
                 o.suffix = render::Suffix::cached;
               },
               .scored = [](uint32_t f) { return f % 2 == 1; }, .state = moving_emitter, .expect_bias = true});
  v.push_back({.name = "splat_replay_moving_occluder", .scene = "cornell", .method = "restir-splat", .frames = 6, .runs = 64,
               .options = [](render::RestirOptions& o) {
                 o.spatial = false;
                 o.suffix = render::Suffix::replay;
               },
               .scored = [](uint32_t f) { return f % 2 == 1; }, .state = moving_occluder});
  // Sub-pixel geometry: foliage's grass blades are narrower than a pixel, so each frame's camera
  // sample of a pixel lands on another blade, side or the ground, and the blades' shadows on the
  // ground are finer than a pixel; a still camera, temporal reuse only. Temporal reuse raises
  // foliage's per-frame error (docs/BENCHMARKS.md, "Temporal reuse on sub-pixel geometry"); this
  // case shows that it is variance, not bias. 64 x 64 (at 16 x 16 a pixel spans whole tufts).
  v.push_back({.name = "foliage_still_temporal", .scene = "foliage", .frames = 8, .runs = 16, .size = 64, .reference_runs = 8,
               .reference_spp = 16,
               .options = [](render::RestirOptions& o) { o.spatial = false; },
               .state = [](const scene::Scene& s, uint32_t) { return s.frame_state(0); }});
  // The albedo control variate (restir_shade.comp) where it acts: chess's board, whose squares meet
  // inside pixels; a still camera so that every frame after the first has the pixel's earlier
  // demodulated radiance. 64 x 64: at 16 x 16 a pixel spans several squares.
  v.push_back({.name = "albedo_cv_chess", .scene = "chess", .frames = 6, .runs = 32, .size = 64, .reference_runs = 8,
               .reference_spp = 128, .state = [](const scene::Scene& s, uint32_t) { return s.frame_state(0); }});
  // restir-multilayer (the ML paper) and its two validation variants: the image (front layer) on
  // carousel and on the two-plane disocclusion, where splats from the back plane's hidden domains
  // land in the pixels the quad uncovers (tests/restir/multilayer_test.cpp checks that they do).
  for (const char* mode : {"active", "uniform", "no-depth-ranges"}) {
    const std::string suffix = std::string(mode) == "active" ? "" : "_" + method_test_name(mode);
    auto options = [mode](render::RestirOptions& o) { strata::options::set_choice(o, "layer_mode", mode); };
    v.push_back({.name = "multilayer_carousel" + suffix, .scene = "carousel", .method = "restir-multilayer", .options = options});
    v.push_back({.name = "multilayer_two_planes" + suffix, .scene = "two-planes", .method = "restir-multilayer", .options = options,
                 .state = front_jumping, .variant = "built", .edit = two_planes_scene});
  }
  // LoD-aware reuse (the LOD paper): every scored frame switches every LoD group between levels 0
  // and 1, so that each temporal shift maps x_1 and x_k with tau (lod_mapping auto = uv here) and
  // multiplies in Eq. 6. lod-cliff: one UV chart, every point maps uniquely; chess: lathed pieces
  // whose UV charts close on a seam; overlap-uv: the mirrored
  // floor and the cube whose six faces share one UV square, where Alg. 1 matches (and, without
  // matching, refuses) the points.
  auto lod_switching = [](uint32_t scene_frame) {
    return [scene_frame](const scene::Scene& s, uint32_t f) { return lod_switched(s, scene_frame, f); };
  };
  // (lod-cliff's reference at 16 spp: its variance share is still under 2%.)
  v.push_back({.name = "lod_cliff_splat", .scene = "lod-cliff", .method = "restir-splat", .frames = 3, .runs = 64,
               .reference_spp = 16, .state = lod_switching(60)});
  v.push_back({.name = "lod_cliff_gather", .scene = "lod-cliff", .method = "restir-gather", .frames = 3, .runs = 64,
               .reference_spp = 16, .state = lod_switching(60)});
  // chess: three lathed pieces of 3 levels each (make_lod_chain), at 32 x 32 so that they cover
  // whole blocks; the rook, queen and pawn all switch.
  for (const char* method : {"splat", "gather"})
    v.push_back({.name = std::string("lod_chess_") + method, .scene = "chess", .method = std::string("restir-") + method, .frames = 3,
                 .runs = 64, .size = 32, .reference_runs = 16, .state = lod_switching(0)});
  v.push_back({.name = "lod_overlap_uv_splat", .scene = "overlap-uv", .method = "restir-splat", .frames = 3, .runs = 64,
               .state = lod_switching(10)});
  v.push_back({.name = "lod_overlap_uv_splat_no_matching", .scene = "overlap-uv", .method = "restir-splat", .frames = 3,
               .runs = 64, .options = [](render::RestirOptions& o) { o.lod_matching = false; }, .state = lod_switching(10)});
  return v;
}

INSTANTIATE_TEST_SUITE_P(Cases, RestirUnbiased, ::testing::ValuesIn(cases()),
                         [](const ::testing::TestParamInfo<Case>& p) { return p.param.name; });

}  // namespace
}  // namespace strata::test
