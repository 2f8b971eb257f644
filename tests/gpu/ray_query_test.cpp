// Ray queries on lavapipe against the CPU brute-force intersector, on every built-in scene at its
// first and a later animation frame (so transformed instances, refits and LoD levels are covered).
#include <algorithm>
#include <random>

#include "gpu/gpu_context.h"
#include "render/ray_probe.h"
#include "scene/scene_io.h"
#include "support/cpu_tracer.h"

namespace strata::test {
namespace {

class RayQuery : public GpuTest, public ::testing::WithParamInterface<std::string> {};

TEST_P(RayQuery, HitsMatchCpuBruteForce) {
  scene::Scene s = scene::builtin_scene(GetParam());
  render::RayProbe probe(gpu_context(), s);
  for (uint32_t frame_index : {0u, 45u}) {
    scene::FrameState frame = s.frame_state(frame_index);
    CpuScene cpu = build_cpu_scene(s, frame);
    // Camera rays over a 24x24 grid plus rays between random points of the scene's bounds.
    std::vector<render::ProbeRay> rays;
    std::vector<CpuRay> cpu_rays;
    const uint32_t n = 24;
    std::mt19937 rng(1234 + frame_index);
    std::uniform_real_distribution<double> u01(0.0, 1.0);
    for (uint32_t y = 0; y < n; ++y) {
      for (uint32_t x = 0; x < n; ++x) {
        CpuRay r = camera_ray(frame.camera, n, n, x, y, u01(rng), u01(rng));
        cpu_rays.push_back(r);
        rays.push_back({glm::vec3(r.origin), glm::vec3(r.direction), 0.0f, 1e30f});
      }
    }
    glm::dvec3 lo(1e300), hi(-1e300);
    for (const auto& t : cpu.triangles) {
      lo = glm::min(lo, glm::min(t.p0, glm::min(t.p1, t.p2)));
      hi = glm::max(hi, glm::max(t.p0, glm::max(t.p1, t.p2)));
    }
    for (int i = 0; i < 256; ++i) {
      glm::dvec3 a = lo + (hi - lo) * glm::dvec3(u01(rng), u01(rng), u01(rng));
      glm::dvec3 b = lo + (hi - lo) * glm::dvec3(u01(rng), u01(rng), u01(rng));
      glm::dvec3 d = glm::normalize(b - a);
      CpuRay r;
      r.origin = a;
      r.direction = d;
      cpu_rays.push_back(r);
      rays.push_back({glm::vec3(a), glm::vec3(d), 0.0f, 1e30f});
    }
    auto gpu_hits = probe.trace(frame, rays);
    ASSERT_EQ(gpu_hits.size(), rays.size());
    size_t disagreements = 0, hits = 0;
    double scale = glm::length(hi - lo);
    for (size_t i = 0; i < rays.size(); ++i) {
      auto c = intersect(cpu, cpu_rays[i]);
      const auto& g = gpu_hits[i];
      bool same = false;
      if (!c && g.t < 0.0f) same = true;
      if (c && g.t >= 0.0f) {
        ++hits;
        // Same triangle and distance, or (on a shared edge / coplanar tie) the same distance.
        double tol = 1e-4 * scale + 1e-4 * c->t;
        same = std::abs(double(g.t) - c->t) < tol;
        if (same && g.instance == c->instance && g.geometry == c->primitive && g.triangle == c->triangle) {
          // The barycentrics to 1e-3, or where the triangle is small (a cloth's cells) the points
          // they name to the distance tolerance.
          const double du = double(g.bary.x) - c->u, dv = double(g.bary.y) - c->v;
          if (std::max(std::abs(du), std::abs(dv)) > 1e-3) {
            const auto t = std::find_if(cpu.triangles.begin(), cpu.triangles.end(), [&](const CpuTriangle& x) {
              return x.instance == c->instance && x.primitive == c->primitive && x.triangle == c->triangle;
            });
            ASSERT_NE(t, cpu.triangles.end());
            EXPECT_LT(glm::length(du * (t->p1 - t->p0) + dv * (t->p2 - t->p0)), tol)
                << "ray " << i << ": barycentrics (" << g.bary.x << ", " << g.bary.y << ") against (" << c->u << ", " << c->v << ")";
          }
        }
      }
      disagreements += !same;
    }
    // Float (GPU) and double (CPU) can disagree only for rays that graze an edge or silhouette:
    // at most 1% of rays, and the rest must agree exactly on hit/miss and distance.
    EXPECT_LE(disagreements, rays.size() / 100) << GetParam() << " frame " << frame_index;
    EXPECT_GT(hits, rays.size() / 4) << "too few hits to test anything";
  }
}

INSTANTIATE_TEST_SUITE_P(BuiltinScenes, RayQuery, ::testing::ValuesIn(scene::builtin_scene_names()),
                         scene_param_name);

}  // namespace
}  // namespace strata::test
