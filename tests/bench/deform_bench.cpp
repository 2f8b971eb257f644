// strata_deform_bench: what deforming meshes cost per frame. A skinned cloth of n x n vertices (the
// characters scene's flag, subdivided; 5 joints) and a morphing sphere of about as many vertices (2
// targets) in an otherwise empty scene; per vertex count, the GPU time of the pass `deform` with the
// BLAS updates that follow it (one PassTimer span), median over frames 2..F-1 of the scene's
// animation, and how many BLAS updates were refits and rebuilds.
// Prints one line per size and writes JSON.
#include <CLI/CLI.hpp>
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include <glm/gtc/matrix_transform.hpp>

#include "gpu/context.h"
#include "gpu/timer.h"
#include "render/scene_gpu.h"
#include "scene/scene_io.h"

namespace {

using namespace strata;

// characters' flag and blob with `cells` x `cells` quads (the flag) and a sphere of about as many vertices.
scene::Scene dense_characters(uint32_t cells) {
  scene::Scene s = scene::builtin_scene("characters");
  for (scene::Instance& inst : s.instances) {
    if (!inst.deforms()) continue;
    scene::Mesh& mesh = s.meshes[inst.lod_meshes.front()];
    scene::Primitive& p = mesh.primitives.front();
    if (inst.skin >= 0) {
      // Resample the cloth: positions on the bind pose's plane, joints and weights by x as the scene does.
      const glm::vec3 lo = *std::min_element(p.positions.begin(), p.positions.end(), [](auto a, auto b) { return a.x + a.y < b.x + b.y; });
      const glm::vec3 hi = *std::max_element(p.positions.begin(), p.positions.end(), [](auto a, auto b) { return a.x + a.y < b.x + b.y; });
      scene::Primitive q;
      q.material = p.material;
      for (uint32_t j = 0; j <= cells; ++j) {
        for (uint32_t i = 0; i <= cells; ++i) {
          const glm::vec2 uv(float(i) / float(cells), float(j) / float(cells));
          const glm::vec3 x(lo.x + (hi.x - lo.x) * uv.x, lo.y + (hi.y - lo.y) * uv.y, lo.z);
          q.positions.push_back(x);
          q.normals.emplace_back(0, 0, 1);
          q.uvs.push_back(uv);
          const float sx = std::clamp((x.x - lo.x) / 0.25f, 0.0f, 4.0f);
          const uint32_t k = std::min(uint32_t(sx), 3u);
          q.joints.emplace_back(k, k + 1, 0, 0);
          q.weights.emplace_back(1.0f - (sx - float(k)), sx - float(k), 0.0f, 0.0f);
        }
      }
      for (uint32_t j = 0; j < cells; ++j)
        for (uint32_t i = 0; i < cells; ++i) {
          const uint32_t a = j * (cells + 1) + i;
          q.indices.insert(q.indices.end(), {a, a + 1, a + cells + 2, a, a + cells + 2, a + cells + 1});
        }
      p = std::move(q);
    } else {
      // The sphere with (cells + 1)^2 vertices: its targets rebuilt for the new vertices.
      const uint32_t segments = std::max<uint32_t>(4, cells), rings = std::max<uint32_t>(2, cells / 2);
      scene::Primitive q;
      q.material = p.material;
      for (uint32_t r = 0; r <= rings; ++r)
        for (uint32_t g = 0; g <= segments; ++g) {
          const float theta = float(M_PI) * float(r) / float(rings), phi = 2.0f * float(M_PI) * float(g) / float(segments);
          const glm::vec3 n(std::sin(theta) * std::cos(phi), -std::cos(theta), std::sin(theta) * std::sin(phi));
          q.positions.push_back(0.25f * n);
          q.normals.push_back(n);
          q.uvs.emplace_back(float(g) / float(segments), float(r) / float(rings));
        }
      for (uint32_t r = 0; r < rings; ++r)
        for (uint32_t g = 0; g < segments; ++g) {
          const uint32_t a = r * (segments + 1) + g, b = a + segments + 1;
          q.indices.insert(q.indices.end(), {a, b, a + 1, a + 1, b, b + 1});
        }
      scene::MorphTarget breathe, squash;
      for (size_t v = 0; v < q.positions.size(); ++v) {
        breathe.positions.push_back(0.3f * q.positions[v]);
        squash.positions.push_back(q.positions[v] * glm::vec3(0.2f, -0.3f, 0.2f));
        squash.normals.emplace_back(0.0f);
      }
      q.targets = {breathe, squash};
      p = std::move(q);
    }
  }
  s.validate();
  return s;
}

double median(std::vector<double> v) {
  std::sort(v.begin(), v.end());
  return v.empty() ? 0.0 : v[v.size() / 2];
}

}  // namespace

int main(int argc, char** argv) {
  CLI::App app("strata_deform_bench: deformation and BLAS update time against vertex count");
  std::vector<uint32_t> cells = {16, 64, 128, 256, 512};
  uint32_t frames = 12;
  std::string out = "deform_bench.json", device;
  app.add_option("--cells", cells, "the cloth's quads per side (its vertices: (cells + 1)^2)");
  app.add_option("--frames", frames, "animation frames per size (the first two are not timed)");
  app.add_option("--out", out, "JSON output");
  app.add_option("--device", device, "Vulkan device name substring");
  CLI11_PARSE(app, argc, argv);

  gpu::ContextOptions co;
  co.device = device;
  gpu::Context ctx(co);
  nlohmann::json results = nlohmann::json::array();
  for (uint32_t n : cells) {
    const scene::Scene s = dense_characters(n);
    render::GpuScene gs(ctx, s, /*keep_history=*/true);
    gpu::PassTimer timer(ctx, 2);
    std::vector<double> deform_ms, update_ms;
    for (uint32_t f = 0; f < frames; ++f) {
      const scene::FrameState state = s.frame_state(f);
      ctx.submit_and_wait([&](VkCommandBuffer cmd) {
        timer.reset(cmd);
        timer.begin(cmd, "deform");
        gs.record_deformation(cmd, state);
        timer.end(cmd);
        timer.begin(cmd, "update");
        gs.record_update(cmd, state);
        timer.end(cmd);
      });
      if (f < 2) continue;
      for (const auto& t : timer.read()) (t.pass == "deform" ? deform_ms : update_ms).push_back(t.ms);
    }
    const uint32_t vertices = gs.deformation()->deformed_vertices();
    const double d = median(deform_ms), u = median(update_ms);
    std::printf("%8u deformed vertices: deform + BLAS updates %.3f ms, TLAS update %.3f ms; BLAS %u refits, %u rebuilds\n", vertices, d,
                u, gs.deformation()->refits(), gs.deformation()->rebuilds());
    results.push_back({{"deformed_vertices", vertices},
                       {"deform_ms_median", d},
                       {"tlas_update_ms_median", u},
                       {"blas_refits", gs.deformation()->refits()},
                       {"blas_rebuilds", gs.deformation()->rebuilds()}});
  }
  std::ofstream(out) << nlohmann::json{{"device", ctx.device_name()}, {"frames", frames}, {"sizes", results}}.dump(2) << "\n";
  return 0;
}
