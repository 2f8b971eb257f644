// The light tree (render/light_tree.h, sampling/light_tree.h): the probabilities it gives a shading
// point sum to one over the lights and are those its choice takes, every light that can reach the
// point has a positive probability (else next-event estimation would miss its light: bias), stratified
// choices land on each light as often as its probability says, and near lights are chosen more often
// than power alone would.
#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <vector>

#include "render/light_tree.h"
#include "scene/builtin/random.h"
#include "scene/scene_io.h"

namespace strata::test {
namespace {

// A many-light table: emissive triangles scattered in a 20 m box (random orientation, a third
// double-sided, instance i / 40, geometry (i / 10) % 4), point and spot lights, two directional.
struct ManyLights {
  render::EmitterTable table;
  std::vector<scene::Light> lights;
};

ManyLights many_lights(uint32_t emitters, uint32_t punctual) {
  ManyLights m;
  scene::builtin::Pcg32 rng(0x11947u);
  auto point = [&](float r) { return glm::vec3(rng.uniform(-r, r), rng.uniform(-r, r), rng.uniform(-r, r)); };
  for (uint32_t i = 0; i < emitters; ++i) {
    const glm::vec3 c = point(10.0f);
    const glm::vec3 p[3] = {c + point(0.3f), c + point(0.3f), c + point(0.3f)};
    const float area = 0.5f * glm::length(glm::cross(p[1] - p[0], p[2] - p[0]));
    uint32_t flags = i % 3 == 0 ? gpu::MATERIAL_DOUBLE_SIDED : 0u;
    float flag_bits;
    std::memcpy(&flag_bits, &flags, sizeof flags);
    m.table.emitters.push_back({glm::vec4(p[0], area), glm::vec4(p[1], 0.0f), glm::vec4(p[2], flag_bits), glm::vec4(1.0f),
                                glm::uvec4(i / 40, (i / 10) % 4, 3 * (i % 10), 0u)});
    m.table.power.push_back(double(area) * rng.uniform(0.1f, 10.0f));
  }
  for (uint32_t l = 0; l < punctual + 2; ++l) {
    scene::Light light;
    light.type = l >= punctual ? scene::LightType::kDirectional : (l % 2 ? scene::LightType::kSpot : scene::LightType::kPoint);
    light.outer_cone = 0.6f;
    m.lights.push_back(light);
    gpu::GpuPunctualLight r{};
    const glm::vec3 dir = glm::normalize(point(1.0f) + glm::vec3(0.0f, -0.5f, 0.0f));
    r.position_range = glm::vec4(point(10.0f), 0.0f);
    r.direction_type = glm::vec4(dir, float(light.type == scene::LightType::kDirectional ? gpu::PUNCTUAL_DIRECTIONAL
                                            : light.type == scene::LightType::kSpot          ? gpu::PUNCTUAL_SPOT
                                                                                             : gpu::PUNCTUAL_POINT));
    m.table.lights.push_back(r);
    m.table.power.push_back(rng.uniform(0.5f, 5.0f));
  }
  return m;
}

uint32_t entries(const render::EmitterTable& t) { return uint32_t(t.emitters.size() + t.lights.size()); }

glm::vec3 random_direction(scene::builtin::Pcg32& rng) {
  for (;;) {
    const glm::vec3 v(rng.uniform(-1.0f, 1.0f), rng.uniform(-1.0f, 1.0f), rng.uniform(-1.0f, 1.0f));
    const float l2 = glm::dot(v, v);
    if (l2 > 1e-4f && l2 <= 1.0f) return v / std::sqrt(l2);
  }
}

TEST(LightTree, ProbabilitiesSumToOneAndAreThoseOfTheChoice) {
  const ManyLights m = many_lights(600, 64);
  const render::LightTree tree = render::build_light_tree(m.table, m.lights, 16);
  ASSERT_EQ(tree.directional.size(), 2u);
  scene::builtin::Pcg32 rng(7u);
  for (int k = 0; k < 40; ++k) {
    const glm::vec3 x(rng.uniform(-12.0f, 12.0f), rng.uniform(-12.0f, 12.0f), rng.uniform(-12.0f, 12.0f));
    // Every fourth without a surface; the others on one, half of them weighing by its cosine.
    const glm::vec4 n = k % 4 == 0 ? glm::vec4(0.0f) : glm::vec4(random_direction(rng), float(k % 2));
    // At most one: a node may reach x where none of its children does (its bounds and cone are
    // looser than theirs, and on a surface its box may cross the surface's plane where theirs lie
    // behind it), and a choice that descends there finds no light (a wasted sample, not bias).
    double sum = 0.0;
    for (uint32_t e = 0; e < entries(m.table); ++e) sum += render::light_tree_pmf(tree, x, n, e);
    EXPECT_LE(sum, 1.0 + 1e-4) << "x " << x.x << " " << x.y << " " << x.z;
    EXPECT_GT(sum, k % 4 == 0 ? 0.9 : 0.25) << "x " << x.x << " " << x.y << " " << x.z;
    for (int j = 0; j < 64; ++j) {
      uint32_t e;
      float pmf;
      if (!render::light_tree_choose(tree, x, n, rng.uniform(0.0f, 1.0f), e, pmf)) continue;
      EXPECT_EQ(pmf, render::light_tree_pmf(tree, x, n, e));  // the same products, bit for bit
    }
  }
}

TEST(LightTree, EveryLightThatReachesThePointHasAPositiveProbability) {
  // At x on a surface of normal n (nodes behind it culled) and at x without one: a light that faces x
  // and lies, at least in part, in front of the surface must keep a positive probability, else
  // next-event estimation would never sample light that the surface scatters (bias).
  const ManyLights m = many_lights(600, 64);
  const render::LightTree tree = render::build_light_tree(m.table, m.lights, 16);
  scene::builtin::Pcg32 rng(11u);
  int reaching = 0, culled = 0, behind = 0;  // emitters facing x; of the others, those the bounds rule out
  for (int k = 0; k < 40; ++k) {
    const glm::vec3 x(rng.uniform(-12.0f, 12.0f), rng.uniform(-12.0f, 12.0f), rng.uniform(-12.0f, 12.0f));
    const glm::vec3 normal = k % 2 == 0 ? glm::vec3(0.0f) : random_direction(rng);
    const glm::vec4 n(normal, float((k / 2) % 2));  // on a surface, every other one weighs by its cosine
    const bool surface = k % 2 != 0;
    for (uint32_t e = 0; e < m.table.emitters.size(); ++e) {
      const auto& t = m.table.emitters[e];
      const glm::vec3 p0(t.p0_area), p1(t.p1_pmf), p2(t.p2_flags);
      const glm::vec3 c = glm::cross(p1 - p0, p2 - p0);
      uint32_t flags;
      std::memcpy(&flags, &t.p2_flags.w, sizeof flags);
      const float facing = glm::dot(c, x - p0);  // the plane's side x is on: the whole triangle faces it or not
      const bool in_front =
          !surface || glm::dot(normal, p0 - x) > 0.0f || glm::dot(normal, p1 - x) > 0.0f || glm::dot(normal, p2 - x) > 0.0f;
      const float pmf = render::light_tree_pmf(tree, x, n, e);
      if ((facing > 0.0f || (flags & gpu::MATERIAL_DOUBLE_SIDED) != 0u) && in_front) {
        ++reaching;
        EXPECT_GT(pmf, 0.0f) << "emitter " << e;
      } else if (pmf == 0.0f) {
        ++culled;
        if (!in_front) ++behind;
      }
    }
    for (uint32_t l = 0; l + 2 < m.lights.size(); ++l) {
      const auto& r = m.table.lights[l];
      const glm::vec3 to_x = glm::normalize(x - glm::vec3(r.position_range));
      const bool lit = m.lights[l].type == scene::LightType::kPoint ||
                       glm::dot(to_x, glm::vec3(r.direction_type)) > std::cos(m.lights[l].outer_cone);
      const bool in_front = !surface || glm::dot(normal, -to_x) > 0.0f;
      const float pmf = render::light_tree_pmf(tree, x, n, uint32_t(m.table.emitters.size()) + l);
      if (lit && in_front) {
        EXPECT_GT(pmf, 0.0f) << "light " << l;
      } else if (!in_front) {
        EXPECT_EQ(pmf, 0.0f) << "light " << l << " behind the surface";
      }
    }
  }
  EXPECT_GT(reaching, 5000);
  EXPECT_GT(culled, 2000);  // the orientation bounds do rule lights out
  EXPECT_GT(behind, 2000);  // and so does the surface at x
}

TEST(LightTree, StratifiedChoicesLandAsOftenAsTheProbabilitySays) {
  const ManyLights m = many_lights(300, 32);
  const render::LightTree tree = render::build_light_tree(m.table, m.lights, 16);
  const glm::vec3 x(1.0f, 2.0f, -3.0f);
  constexpr uint32_t n = 1u << 18;
  std::vector<uint32_t> count(entries(m.table), 0u);
  uint32_t missed = 0;
  for (uint32_t i = 0; i < n; ++i) {
    uint32_t e;
    float pmf;
    if (render::light_tree_choose(tree, x, glm::vec4(0.0f), (float(i) + 0.5f) / float(n), e, pmf)) ++count.at(e);
    else ++missed;
  }
  double sum = 0.0;
  // Each leaf owns an interval of u as long as its probability (to float rounding of the rescaled u
  // over about 20 levels): stratified counts are n pmf to within a few strata.
  for (uint32_t e = 0; e < entries(m.table); ++e) {
    sum += render::light_tree_pmf(tree, x, glm::vec4(0.0f), e);
    EXPECT_NEAR(double(count[e]), double(n) * render::light_tree_pmf(tree, x, glm::vec4(0.0f), e), 4.0) << "entry " << e;
  }
  EXPECT_NEAR(double(missed), double(n) * (1.0 - sum), 8.0);
}

TEST(LightTree, ChoosesNearLightsMoreOftenThanPowerDoes) {
  // 64 equal point lights 2 m apart along a 126 m street: at 1 m from the first, power selection
  // gives it 1/64; its share of the irradiance there is above 0.6.
  render::EmitterTable table;
  std::vector<scene::Light> lights(64);
  for (uint32_t l = 0; l < 64; ++l) {
    gpu::GpuPunctualLight r{};
    r.position_range = glm::vec4(2.0f * float(l), 3.0f, 0.0f, 0.0f);
    r.direction_type = glm::vec4(0.0f, -1.0f, 0.0f, float(gpu::PUNCTUAL_POINT));
    table.lights.push_back(r);
    table.power.push_back(1.0);
  }
  const render::LightTree tree = render::build_light_tree(table, lights, 0);
  const glm::vec4 floor(0.0f, 1.0f, 0.0f, 1.0f);
  EXPECT_GT(render::light_tree_pmf(tree, glm::vec3(0.0f, 2.0f, 0.0f), floor, 0), 0.25f);
  EXPECT_LT(render::light_tree_pmf(tree, glm::vec3(0.0f, 2.0f, 0.0f), floor, 63), 1.0f / 640.0f);
}

TEST(LightTree, WeighsByTheReceiversCosineOnlyWhereAsked) {
  // Two equal point lights 2 m from a point on a floor: one above it, one almost in the floor's
  // plane (cosine 0.05). Weighed by the receiver's cosine (a rough floor) the second is chosen about
  // a twentieth as often as the first; not weighed (a glossy floor, whose f cos theta_i stays large
  // near its plane) about as often.
  render::EmitterTable table;
  std::vector<scene::Light> lights(2);
  const float c = 0.05f, sn = std::sqrt(1.0f - c * c);
  for (const glm::vec3 p : {glm::vec3(0.0f, 2.0f, 0.0f), glm::vec3(2.0f * sn, 2.0f * c, 0.0f)}) {
    gpu::GpuPunctualLight r{};
    r.position_range = glm::vec4(p, 0.0f);
    r.direction_type = glm::vec4(0.0f, -1.0f, 0.0f, float(gpu::PUNCTUAL_POINT));
    table.lights.push_back(r);
    table.power.push_back(1.0);
  }
  const render::LightTree tree = render::build_light_tree(table, lights, 0);
  const glm::vec3 x(0.0f);
  const glm::vec4 rough(0, 1, 0, 1), glossy_floor(0, 1, 0, 0);
  const float weighed = render::light_tree_pmf(tree, x, rough, 1) / render::light_tree_pmf(tree, x, rough, 0);
  const float glossy = render::light_tree_pmf(tree, x, glossy_floor, 1) / render::light_tree_pmf(tree, x, glossy_floor, 0);
  EXPECT_NEAR(weighed, c, 0.01f);
  EXPECT_NEAR(glossy, 1.0f, 0.01f);
}

TEST(LightTree, FindsEachEmittersEntryAndKeepsItsBounds) {
  const ManyLights m = many_lights(600, 64);
  const render::LightTree tree = render::build_light_tree(m.table, m.lights, 16);
  for (uint32_t e = 0; e < m.table.emitters.size(); ++e) {
    const glm::uvec4 s = m.table.emitters[e].surface;
    EXPECT_EQ(tree.entry_of(s.x, s.y, s.z), e);
    EXPECT_EQ(tree.entry_of(s.x, s.y, s.z + 1), gpu::LIGHT_TREE_NONE);  // triangles are 3 apart
  }
  EXPECT_EQ(tree.entry_of(15, 0, 0), gpu::LIGHT_TREE_NONE);  // an instance without emitters
  EXPECT_EQ(tree.entry_of(99, 0, 0), gpu::LIGHT_TREE_NONE);  // no such instance
  for (uint32_t i = 0; i < tree.nodes.size(); ++i) {
    const gpu::GpuLightNode& n = tree.nodes[i];
    if (n.links.y & gpu::LIGHT_NODE_LEAF) continue;
    const gpu::GpuLightNode& a = tree.nodes[i + 1];
    const gpu::GpuLightNode& b = tree.nodes[n.links.x];
    EXPECT_NEAR(n.lo_power.w, a.lo_power.w + b.lo_power.w, 1e-4 * n.lo_power.w);
    for (int k = 0; k < 3; ++k) {
      EXPECT_LE(n.lo_power[k], std::min(a.lo_power[k], b.lo_power[k]));
      EXPECT_GE(n.hi_cos_o[k], std::max(a.hi_cos_o[k], b.hi_cos_o[k]));
    }
  }
  for (const glm::uvec4& t : tree.trails) EXPECT_TRUE(t.z == gpu::LIGHT_TREE_NONE || t.z <= gpu::LIGHT_TREE_MAX_DEPTH);
}

}  // namespace
}  // namespace strata::test
