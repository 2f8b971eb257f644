// restir-multilayer's pixel-layer domains (the ML paper; docs/ARCHITECTURE.md, "Pixel layers") on
// the hand-built two-plane scene of tests/support (test::two_planes):
// - a deep layer's own integral (ML Eq. 3 with the camera's visibility left out) matches the back
//   plane rendered with the front quad removed, with the unbiasedness harness's tolerance;
// - it holds only its domain (ML Eq. 4): where the front quad covers part of a pixel, or thin
//   stripes lie inside the back plane's depth range, it matches the hidden part of each pixel;
// - domain propagation (ML 4.3): while the front quad jumps between two places, the back plane's
//   domains are active exactly where it is hidden and was visible the frame before, and the pixels
//   it reappears in are covered by splats from those domains, and with the deep backup the held
//   pixels no splat reached too;
// - the silhouette band: hidden domains far from every silhouette are dormant and wake before
//   they are uncovered (coverage as without the band, fewer active domains);
// - numerics: depth ranges at t near 0 and at 1e5, grazing views, 8 layers of a stack of 12 planes,
//   every pixel disoccluded at once (a teleporting camera): every pixel finite.
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <functional>
#include <string>

#include <glm/gtc/matrix_transform.hpp>
#include <glm/gtc/quaternion.hpp>

#include "gpu/gpu_context.h"
#include "options/option_table.h"
#include "render/renderer.h"
#include "support/test_scenes.h"
#include "support/unbiasedness.h"

namespace strata::test {
namespace {

// Where the front quad is (its x offset) in frame f of the jumping sequence.
float jump_offset(uint32_t f) { return f % 2 == 0 ? -0.3f : 0.3f; }

scene::FrameState with_front_at(const scene::Scene& s, float x) {
  scene::FrameState st = s.frame_state(0);
  const uint32_t i = instance_named(s, "front");
  st.transforms[i] = glm::translate(glm::mat4(1.0f), {x, 0.0f, 0.0f});
  return st;
}

// Whether the centre ray of pixel (px, py) of a size x size image meets the front quad (half size h,
// at x offset ox): two_planes' camera is at z = 4 looking down -Z, the quad at z = 1.
bool behind_front(uint32_t px, uint32_t py, uint32_t size, float h, float ox) {
  const float t = std::tan(0.5f * 0.6f);  // two_planes' yfov
  const float x = 3.0f * t * (2.0f * (float(px) + 0.5f) / float(size) - 1.0f);
  const float y = 3.0f * t * (2.0f * (float(py) + 0.5f) / float(size) - 1.0f);
  return std::abs(x - ox) <= h && std::abs(y) <= h;
}

uint64_t count_pixels(uint32_t size, const std::function<bool(uint32_t, uint32_t)>& pred) {
  uint64_t n = 0;
  for (uint32_t y = 0; y < size; ++y)
    for (uint32_t x = 0; x < size; ++x) n += pred(x, y);
  return n;
}

// sum += w * x, pixel by pixel; an empty sum starts at zero (means and differences over frames).
void add_scaled(image::Image& sum, const image::Image& x, float w) {
  if (sum.rgba.empty()) {
    sum = x;
    std::fill(sum.rgba.begin(), sum.rgba.end(), 0.0f);
  }
  for (size_t i = 0; i < sum.rgba.size(); ++i) sum.rgba[i] += w * x.rgba[i];
}

render::RenderSettings multilayer_settings(uint32_t size, uint32_t seed) {
  render::RenderSettings rs;
  rs.width = size;
  rs.height = size;
  rs.method = "restir-multilayer";
  rs.max_depth = 2;
  rs.seed = seed;
  rs.restir.layers = 2;
  // The ML paper's scheme: every activated deep domain samples (the cases below count them, and some
  // hide the whole view, where the band would leave every one dormant); the band and the reveal
  // prediction have their own case.
  rs.restir.silhouette_band = 0;
  rs.restir.reveal_lookahead = 0;
  return rs;
}

class MultilayerDomains : public GpuTest {};

// Layer 1's estimate (view_layer 1) of the back plane hidden behind a front quad that covers the
// whole view, against `pt` of the back plane alone (sound: two_planes' back plane has the same
// radiance with and without the quad at max_depth 2, see test_scenes.h; the harness's z-test has a
// family-wise false-failure probability of 1e-4). 384 sequences: at 48 the grazing light's heavy
// tails left the standard errors too small (a block |z| of 5.2 that fell to 2.4 at 768). Active mode: the quad is out of view in frame 0,
// so frame 1's deep domains are those propagated from frame 0's front layer (and each frame's
// propagated on); uniform: every deep domain is active from frame 0.
TEST_F(MultilayerDomains, DeepLayerEstimatesItsHiddenSurface) {
  const uint32_t size = 16, frames = 4;
  const scene::Scene s = two_planes(1.5f);
  const scene::Scene bare = two_planes(0.0f);
  RunningImage reference(size, size);
  for (uint32_t r = 0; r < 128; ++r) {
    render::RenderSettings rs;
    rs.width = rs.height = size;
    rs.spp = 512;
    rs.max_depth = 2;
    rs.seed = 90000 + r;
    render::Renderer renderer(gpu_context(), bare, rs);
    reference.add(renderer.render(bare.frame_state(0), 0).image);
  }
  for (const char* mode : {"active", "uniform"}) {
    RunningImage method(size, size);
    for (uint32_t r = 0; r < 384; ++r) {
      render::RenderSettings rs = multilayer_settings(size, 1000 + r);
      strata::options::set_choice(rs.restir, "layer_mode", mode);
      rs.restir.view_layer = 1;
      render::Renderer renderer(gpu_context(), s, rs);
      image::Image mean;
      for (uint32_t f = 0; f < frames; ++f) {
        const bool active = std::string(mode) == "active";
        auto res = renderer.render(with_front_at(s, active && f == 0 ? 4.0f : 0.0f), f);
        for (float v : res.image.rgba) ASSERT_TRUE(std::isfinite(v)) << mode << " frame " << f;
        if (f == 0) continue;  // active: no deep domain yet
        EXPECT_EQ(res.stats.reuse.at("domains.active_layer_1"), uint64_t(size) * size) << mode << " frame " << f;
        add_scaled(mean, res.image, 1.0f / float(frames - 1));
      }
      method.add(mean);
    }
    BiasReport report = compare_to_reference(method, reference, 4);
    std::printf("layer 1 (%s) vs the back plane alone: %s\n", mode, report.describe().c_str());
    EXPECT_TRUE(report.passed) << mode << ": " << report.describe();
  }
}

// Six black stripes 2 cm in front of the back plane (0.5% of the camera distance, inside one depth
// range of e = 1%), each 5 cm wide (a third of a pixel at 16 x 16) and 1 m long, over the lit right
// half of the back plane. A camera ray through a stripe has the stripe as its first hit from L_i
// (ML Eq. 4), so the back-plane point behind it, though inside the same depth range, is in no
// domain; the light (off to the right, low) still reaches that point through the 2 cm gap.
constexpr uint32_t k_stripes = 6;
scene::Scene planes_with_stripes(float front_half) {
  scene::Scene s = two_planes(front_half);
  scene::Material m;
  m.name = "stripe";
  m.base_color = glm::vec3(0.0f);
  m.specular = 0.0f;
  s.materials.push_back(m);
  scene::Mesh stripe = quad_mesh(0.5f, 0.02f, uint32_t(s.materials.size() - 1));
  stripe.name = "stripe";
  s.meshes.push_back(std::move(stripe));
  for (uint32_t j = 0; j < k_stripes; ++j) {
    scene::Instance inst;
    inst.name = "stripe" + std::to_string(j);
    inst.lod_meshes = {uint32_t(s.meshes.size() - 1)};
    s.instances.push_back(inst);
  }
  s.validate();
  return s;
}

// Frame f of the stripe case: the front quad (if any) out of view in frame 0, then over the lit
// right half of the back plane (x = 0.45); the stripes on the centres of pixel columns 10..15 in
// even frames and half a pixel to the right in odd ones, always behind the front quad from frame 1.
scene::FrameState stripes_frame(const scene::Scene& s, uint32_t f) {
  const float pixel = 2.0f * 4.0f * std::tan(0.3f) / 16.0f;  // a pixel's width on the back plane (yfov 0.6, 16 x 16)
  scene::FrameState st = s.frame_state(0);
  for (uint32_t i = 0; i < s.instances.size(); ++i) {
    const std::string& name = s.instances[i].name;
    if (name == "front") st.transforms[i] = glm::translate(glm::mat4(1.0f), {f == 0 ? 4.0f : 0.45f, 0.0f, 0.0f});
    if (name.rfind("stripe", 0) == 0) {
      const float x = (float(std::stoi(name.substr(6))) + 10.5f - 8.0f + (f % 2 == 1 ? 0.5f : 0.0f)) * pixel;
      st.transforms[i] = glm::scale(glm::translate(glm::mat4(1.0f), {x, 0.0f, 0.0f}), {0.05f, 1.0f, 1.0f});
    }
  }
  return st;
}

// Layer 2 holds its own domain and nothing else (ML Eq. 3 and 4 with the active scheme's depth
// ranges), against the hidden part of each pixel: pt of the scene without the front quad minus pt
// with it (the front quad is black at max_depth 2: nothing lights its upper side; test_scenes.h).
// The front quad's edges cross pixels (half size 0.528: 33-45% of each edge pixel is open), whose
// layer-2 canonical samples must skip the camera rays that miss the quad (Eq. 4's "hidden from
// the camera"; dropping that test fails here). The stripes put two surfaces inside one depth range:
// back-plane samples splatted along rays that now pass through a stripe must be refused by ML
// Fig. 3's range-restricted query.
TEST_F(MultilayerDomains, DeepLayerHoldsOnlyItsDomain) {
  const uint32_t size = 16, frames = 4;
  const float h = 0.528f;
  const scene::Scene s = planes_with_stripes(h);
  const scene::Scene bare = planes_with_stripes(0.0f);
  RunningImage reference(size, size);
  for (uint32_t r = 0; r < 128; ++r) {
    image::Image hidden;
    for (uint32_t f = 1; f < frames; ++f) {
      render::RenderSettings rs;
      rs.width = rs.height = size;
      rs.spp = 512;
      rs.max_depth = 2;
      rs.seed = 70000 + 8 * r + f;
      const auto all = render::Renderer(gpu_context(), bare, rs).render(stripes_frame(bare, f), 0).image;
      rs.seed += 4;
      const auto seen = render::Renderer(gpu_context(), s, rs).render(stripes_frame(s, f), 0).image;
      add_scaled(hidden, all, 1.0f / float(frames - 1));
      add_scaled(hidden, seen, -1.0f / float(frames - 1));
    }
    reference.add(hidden);
  }
  const uint64_t behind = count_pixels(size, [&](uint32_t x, uint32_t y) { return behind_front(x, y, size, h, 0.45f); });
  RunningImage method(size, size);
  for (uint32_t r = 0; r < 384; ++r) {
    render::RenderSettings rs = multilayer_settings(size, 5000 + r);
    rs.restir.view_layer = 1;
    render::Renderer renderer(gpu_context(), s, rs);
    image::Image mean;
    for (uint32_t f = 0; f < frames; ++f) {
      auto res = renderer.render(stripes_frame(s, f), f);
      for (float v : res.image.rgba) ASSERT_TRUE(std::isfinite(v)) << "frame " << f;
      if (f == 0) continue;  // no deep domain yet
      ASSERT_EQ(res.stats.reuse.at("domains.active_layer_1"), behind) << "frame " << f << ": every hidden domain active";
      add_scaled(mean, res.image, 1.0f / float(frames - 1));
    }
    method.add(mean);
  }
  BiasReport report = compare_to_reference(method, reference, 2);
  std::printf("layer 1 with the stripes vs the hidden part of each pixel: %s\n", report.describe().c_str());
  EXPECT_TRUE(report.passed) << report.describe();
}

// ML 4.3 on the jumping quad (hole filling off, so active domains are the propagated ones only):
// frame f's active deep domains are the pixels behind the quad that saw the back plane in frame
// f - 1 (the overlap of the two places is never visible, so never active); from frame 2 on the
// pixels the quad uncovers are exactly frame f - 1's active deep domains, so they are covered.
TEST_F(MultilayerDomains, HiddenDomainsStayActiveAndCoverTheirDisocclusion) {
  const uint32_t size = 32;
  const float h = 0.5f;
  const scene::Scene s = two_planes(h, 0.5f);
  render::RenderSettings rs = multilayer_settings(size, 7);
  rs.restir.hole_fill_radius = 0;
  render::Renderer renderer(gpu_context(), s, rs);
  for (uint32_t f = 0; f < 5; ++f) {
    auto r = renderer.render(with_front_at(s, jump_offset(f)), f);
    const auto& reuse = r.stats.reuse;
    auto behind = [&](uint32_t g) {
      return [=](uint32_t x, uint32_t y) { return behind_front(x, y, size, h, jump_offset(g)); };
    };
    const uint64_t hidden = count_pixels(size, behind(f));
    // The uniform census walks every fourth pixel each way in active mode (domain_build.comp).
    EXPECT_NEAR(double(reuse.at("domains.uniform_deep")), double(hidden), 0.2 * double(hidden) + 64.0) << "frame " << f;
    if (f == 0) {
      EXPECT_EQ(reuse.at("domains.active_layer_1"), 0u) << "no previous frame: front layer only";
      continue;
    }
    const uint64_t newly_hidden = count_pixels(size, [&](uint32_t x, uint32_t y) { return behind(f)(x, y) && !behind(f - 1)(x, y); });
    const uint64_t uncovered = count_pixels(size, [&](uint32_t x, uint32_t y) { return !behind(f)(x, y) && behind(f - 1)(x, y); });
    const uint64_t active = reuse.at("domains.active_layer_1"), disoccluded = reuse.at("domains.disoccluded"),
                   covered = reuse.at("domains.disoccluded_covered"), held = reuse.at("domains.disoccluded_held");
    std::printf("frame %u: hidden %llu, active deep %llu (expected %llu), disoccluded %llu (expected %llu), held %llu, covered %llu\n", f,
                (unsigned long long)hidden, (unsigned long long)active, (unsigned long long)newly_hidden,
                (unsigned long long)disoccluded, (unsigned long long)uncovered, (unsigned long long)held, (unsigned long long)covered);
    EXPECT_EQ(active, newly_hidden) << "frame " << f;
    EXPECT_EQ(disoccluded, uncovered) << "frame " << f;
    // A deep domain's samples lie in its hidden part of the pixel (ML Eq. 4), so a pixel the quad's
    // edge crosses may hold none: about one column of the strip (9%) goes uncovered.
    if (f == 1) {
      EXPECT_EQ(covered, 0u) << "frame 0 had no deep domain";
      EXPECT_EQ(held, 0u) << "frame 0 had no deep domain";
    } else {
      EXPECT_GE(double(covered), 0.85 * double(disoccluded)) << "frame " << f;
      // Held: the uncovered strip lay in the depth ranges of the previous frame's active deep domains.
      EXPECT_GE(double(held), 0.85 * double(disoccluded)) << "frame " << f;
      EXPECT_LE(held, disoccluded) << "frame " << f;
    }
  }
}

// The deep backup (restir_splat_resample.comp; docs/ARCHITECTURE.md, "Pixel layers": the deep backup) on the
// jumping quad: a disoccluded pixel whose hit an active previous deep domain held takes that
// domain's reservoir as its backup sample, so the held pixels a deep splat missed (those the quad's
// edge crosses) get history too. Off, coverage is the splats' alone. Unbiasedness with it:
// restir_unbiased_test.cpp (multilayer_two_planes, multilayer_carousel).
TEST_F(MultilayerDomains, DeepBackupCoversTheHeldPixelsSplatsMissed) {
  const uint32_t size = 32;
  const scene::Scene s = two_planes(0.5f, 0.5f);
  for (const bool deep_backup : {true, false}) {
    render::RenderSettings rs = multilayer_settings(size, 7);
    rs.restir.hole_fill_radius = 0;
    rs.restir.deep_backup = deep_backup;
    render::Renderer renderer(gpu_context(), s, rs);
    uint64_t held = 0, covered = 0, splatted = 0, backup = 0, selected = 0;
    for (uint32_t f = 0; f < 5; ++f) {
      auto r = renderer.render(with_front_at(s, jump_offset(f)), f);
      if (f < 2) continue;  // frame 1 has no previous deep domain
      const auto& reuse = r.stats.reuse;
      held += reuse.at("domains.disoccluded_held");
      covered += reuse.at("domains.disoccluded_covered");
      splatted += reuse.at("domains.disoccluded_splatted");
      EXPECT_EQ(reuse.count("domains.disoccluded_backup"), deep_backup ? 1u : 0u) << "reported with the deep backup only";
      EXPECT_EQ(reuse.count("splat.backup_selected"), deep_backup ? 1u : 0u);
      if (deep_backup) {
        backup += reuse.at("domains.disoccluded_backup");
        selected += reuse.at("splat.backup_selected");
      }
    }
    std::printf("deep_backup %s, frames 2..4: held %llu, covered %llu (by splats %llu, by the backup %llu), backup selected %llu\n",
                deep_backup ? "on" : "off", (unsigned long long)held, (unsigned long long)covered, (unsigned long long)splatted,
                (unsigned long long)backup, (unsigned long long)selected);
    EXPECT_GT(held, 0u) << "the case must uncover pixels a previous deep domain held";
    EXPECT_LT(splatted, held) << "the case must have held pixels no deep splat reached";
    if (deep_backup) {
      // A held pixel the quad's edge crossed may have a deep domain with an empty reservoir (its
      // samples lie in the hidden part of the pixel: HiddenDomainsStayActiveAndCoverTheirDisocclusion).
      EXPECT_GE(double(backup), 0.9 * double(held)) << "a held pixel takes its deep domain's reservoir";
      EXPECT_LE(backup, held);
      EXPECT_GE(covered, backup) << "covered: a splat or the backup";
      EXPECT_GT(covered, splatted) << "the backup reaches held pixels no splat reached";
      EXPECT_GT(selected, 0u);
    } else {
      EXPECT_EQ(covered, splatted);
    }
  }
}

// The silhouette band and the reveal prediction (domain_fill.comp): a quad 14 px wide slides right
// 1 px a frame over the back plane. The back-plane pixels its leading edge hides propagate on while
// hidden; with band 2 the ones farther than 2 px from every silhouette are dormant (tracked, not
// sampled), and they become active again before the trailing edge uncovers them. The reveal
// prediction (lookahead 3, no band) keeps active only the ones the trailing edge uncovers within 3
// frames: not those at the leading edge or under the quad's top and bottom edges, which the band
// keeps. Both leave what is tracked and what is covered as they are without them, with fewer active
// domains, the prediction fewer than the band. (Propagation reads geometry only: tracked = active +
// dormant is exact.)
TEST_F(MultilayerDomains, DormancyKeepsCoverageWithFewerActiveDomains) {
  const uint32_t size = 32, frames = 20, uncovering = 15;  // from frame 15 the trailing edge uncovers pixels seen before
  const float h = 0.4f;
  const scene::Scene s = two_planes(h, 0.5f);
  auto offset = [](uint32_t f) { return -0.5f + 0.058f * float(f); };
  struct Totals {
    uint64_t active = 0, dormant = 0, disoccluded = 0, covered = 0;
  };
  auto run = [&](uint32_t band, uint32_t lookahead) {
    render::RenderSettings rs = multilayer_settings(size, 11);
    rs.restir.hole_fill_radius = 0;
    rs.restir.silhouette_band = band;
    rs.restir.reveal_lookahead = lookahead;
    const bool dormancy = band > 0 || lookahead > 0;
    render::Renderer renderer(gpu_context(), s, rs);
    Totals t;
    for (uint32_t f = 0; f < frames; ++f) {
      auto r = renderer.render(with_front_at(s, offset(f)), f);
      for (float v : r.image.rgba) EXPECT_TRUE(std::isfinite(v)) << "band " << band << " lookahead " << lookahead << " frame " << f;
      const auto& reuse = r.stats.reuse;
      const uint64_t dormant = dormancy ? reuse.at("domains.dormant") : 0;
      std::printf("band %u lookahead %u frame %u: active deep %llu, dormant %llu, disoccluded %llu, covered %llu\n", band, lookahead, f,
                  (unsigned long long)reuse.at("domains.active_layer_1"), (unsigned long long)dormant,
                  (unsigned long long)reuse.at("domains.disoccluded"), (unsigned long long)reuse.at("domains.disoccluded_covered"));
      EXPECT_EQ(reuse.count("domains.dormant"), dormancy ? 1u : 0u);
      t.active += reuse.at("domains.active_layer_1");
      t.dormant += dormant;
      if (f < uncovering) continue;
      t.disoccluded += reuse.at("domains.disoccluded");
      t.covered += reuse.at("domains.disoccluded_covered");
    }
    return t;
  };
  const Totals off = run(0, 0), band = run(2, 0), predicted = run(0, 3);
  EXPECT_GE(double(off.covered), 0.6 * double(off.disoccluded)) << "the case must uncover pixels the camera saw";
  for (const auto& [name, t] : {std::pair{"band", band}, std::pair{"prediction", predicted}}) {
    EXPECT_EQ(t.active + t.dormant, off.active) << name << " changes what samples, not what is tracked";
    EXPECT_EQ(t.disoccluded, off.disoccluded) << name;
    // (A pixel the edge crosses may hold no sample of the hidden part: ML Eq. 4; hence not 100%.)
    EXPECT_GE(double(t.covered), 0.85 * double(off.covered)) << name << ": dormant domains wake before they are uncovered";
  }
  EXPECT_LT(double(band.active), 0.7 * double(off.active));
  EXPECT_LT(double(predicted.active), 0.7 * double(band.active)) << "the prediction leaves the leading edge dormant";
}

// Every pixel finite and every active domain's estimate too (view_layer 1), on views that stress
// the depth ranges and the layer walk.
struct NumericsCase {
  const char* name;
  uint32_t layers;
  std::string mode;
  std::function<scene::Scene()> scene;
  std::function<scene::FrameState(const scene::Scene&, uint32_t)> state;
};

// twelve 4 m quads 5 cm apart at z = 0 .. -0.55 (a stack seen face on: 12 front faces per ray).
scene::Scene plane_stack() {
  scene::Scene s = two_planes(0.0f, 0.5f);
  for (uint32_t k = 0; k < 12; ++k) {
    scene::Instance inst = s.instances[0];
    inst.name = "stack" + std::to_string(k);
    inst.transform = glm::translate(glm::mat4(1.0f), {0.0f, 0.0f, -0.05f * float(k + 1)});
    s.instances.push_back(inst);
  }
  return s;
}

scene::FrameState look(const scene::Scene& s, glm::vec3 eye, glm::vec3 target, float yfov) {
  scene::FrameState st = s.frame_state(0);
  st.camera.position = eye;
  st.camera.orientation = glm::normalize(glm::quatLookAtRH(glm::normalize(target - eye), glm::vec3(0.0f, 1.0f, 0.0f)));
  st.camera.yfov = yfov;
  return st;
}

std::vector<NumericsCase> numerics_cases() {
  auto planes = [] { return two_planes(0.5f, 0.5f); };
  return {
      // The front quad 1e-4 in front of the camera: depth ranges of width 2e-6.
      {"near", 3, "active", planes, [](const scene::Scene& s, uint32_t f) { return look(s, {0.01f * float(f), 0.0f, 1.0001f}, {0, 0, -1}, 0.6f); }},
      // 1e5 away through a narrow lens: the ranges are 2e3 wide, the planes 1 m apart.
      {"far", 3, "active", planes, [](const scene::Scene& s, uint32_t f) { return look(s, {0.0f, 0.0f, 1e5f + float(f)}, {0, 0, 0}, 2e-5f); }},
      // Nearly edge-on: the hits slide far along the planes between pixels.
      {"grazing", 3, "active", planes, [](const scene::Scene& s, uint32_t f) { return look(s, {0.0f, -3.0f, 1.02f + 0.01f * float(f)}, {0, 2, 0.9f}, 0.6f); }},
      {"stack_8_layers", 8, "active", plane_stack, [](const scene::Scene& s, uint32_t f) { return look(s, {0.05f * float(f), 0, 3}, {0, 0, 0}, 0.6f); }},
      {"stack_8_layers_uniform", 8, "uniform", plane_stack, [](const scene::Scene& s, uint32_t f) { return look(s, {0.05f * float(f), 0, 3}, {0, 0, 0}, 0.6f); }},
      // Every other frame the camera jumps through the front quad (to 10 cm in front of the back
      // plane): everything it sees there was hidden behind the quad from the previous camera.
      {"teleport", 3, "active", planes, [](const scene::Scene& s, uint32_t f) {
         return f % 2 == 0 ? look(s, {0, 0, 4}, {0, 0, 0}, 0.6f) : look(s, {0.0f, 0.0f, 0.1f}, {0, 0, 0}, 0.6f);
       }},
  };
}

class MultilayerNumerics : public GpuTest, public ::testing::WithParamInterface<NumericsCase> {};

TEST_P(MultilayerNumerics, EveryPixelAndLayerIsFinite) {
  const NumericsCase& c = GetParam();
  const scene::Scene s = c.scene();
  for (uint32_t view : {0u, 1u}) {
    render::RenderSettings rs = multilayer_settings(16, 3);
    rs.max_depth = 4;
    rs.restir.layers = c.layers;
    strata::options::set_choice(rs.restir, "layer_mode", c.mode);
    rs.restir.view_layer = view;
    render::Renderer renderer(gpu_context(), s, rs);
    uint64_t rejected = 0, deepest = 0, disoccluded = 0;
    for (uint32_t f = 0; f < 4; ++f) {
      auto r = renderer.render(c.state(s, f), f);
      for (float v : r.image.rgba) ASSERT_TRUE(std::isfinite(v) && v >= 0.0f) << c.name << " view " << view << " frame " << f;
      rejected += r.stats.nonfinite_rejected;
      deepest = std::max<uint64_t>(deepest, r.stats.reuse.at("domains.active_layer_" + std::to_string(c.layers - 1)));
      if (f > 0) disoccluded = std::max<uint64_t>(disoccluded, r.stats.reuse.at("domains.disoccluded"));
    }
    std::printf("%s (view %u): rejected %llu, deepest layer's active domains (max) %llu, disoccluded (max) %llu\n", c.name, view,
                (unsigned long long)rejected, (unsigned long long)deepest, (unsigned long long)disoccluded);
    if (c.mode == "uniform") {
      EXPECT_GT(deepest, 0u) << c.name << ": the 8th layer exists on the stack";
    }
    if (std::string(c.name) == "teleport") {
      EXPECT_GE(disoccluded, 16u * 16u * 9 / 10) << "the jump disoccludes the whole image";
    }
  }
}

// The ML paper's "more initial spp" baseline (Fig. 9) for the splat methods: the splat sort runs
// before the initial pass, and exactly the front-layer pixels no splat reached (temporal.no_history)
// trace disocclusion_initial_candidates paths; restir-multilayer (by default, 8) only those of them
// its domain_build found disoccluded, which no deep splat covered, not the landing holes of
// surfaces that stayed in view. Its unbiasedness: restir_unbiased_test.cpp.
TEST_F(MultilayerDomains, DisocclusionBoostTakesThePixelsNoSplatReached) {
  const scene::Scene s = two_planes(0.5f, 0.5f);
  for (const char* method : {"restir-splat", "restir-multilayer"}) {
    render::RenderSettings rs = multilayer_settings(32, 5);
    rs.method = method;
    if (rs.method == "restir-splat") rs.restir.disocclusion_initial_candidates = 4;  // restir-multilayer: its default
    render::Renderer renderer(gpu_context(), s, rs);
    uint64_t boosted_total = 0, holes_total = 0;
    for (uint32_t f = 0; f < 4; ++f) {
      auto r = renderer.render(with_front_at(s, jump_offset(f)), f);
      if (f == 0) continue;
      const uint64_t boosted = r.stats.reuse.at("initial.disocclusion_boosted");
      const uint64_t holes = r.stats.reuse.at("temporal.no_history");
      if (rs.method == "restir-splat") {
        EXPECT_EQ(boosted, holes) << method << " frame " << f;
      } else {
        const uint64_t uncovered = r.stats.reuse.at("domains.disoccluded") - r.stats.reuse.at("domains.disoccluded_splatted");
        EXPECT_LE(boosted, std::min(holes, uncovered)) << method << " frame " << f;
      }
      boosted_total += boosted;
      holes_total += holes;
    }
    EXPECT_GT(boosted_total, 0u) << method << ": the jumping quad leaves pixels no splat reaches";
    if (rs.method == "restir-multilayer") {
      EXPECT_LT(boosted_total, holes_total) << "landing holes of surfaces in view take initial_candidates";
    }
    std::printf("%s: %llu boosted of %llu holes over frames 1..3\n", method, (unsigned long long)boosted_total,
                (unsigned long long)holes_total);
  }
}

INSTANTIATE_TEST_SUITE_P(Views, MultilayerNumerics, ::testing::ValuesIn(numerics_cases()),
                         [](const ::testing::TestParamInfo<NumericsCase>& p) { return std::string(p.param.name); });

}  // namespace
}  // namespace strata::test
