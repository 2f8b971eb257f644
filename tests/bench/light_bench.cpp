// strata_light_bench: what punctual lights cost. Frame time (median gpu_ms_total of frames 1..F-1)
// of pt and restir-gather on cornell as built and with N punctual lights added (point and spot
// lights spread under the ceiling, all in the light table with the ceiling quad), at 1 spp.
// Prints one line per (method, lights) pair and writes JSON.
#include <CLI/CLI.hpp>
#include <algorithm>
#include <cstdio>
#include <fstream>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include <glm/gtc/matrix_transform.hpp>

#include "gpu/context.h"
#include "render/renderer.h"
#include "scene/scene_io.h"

namespace {

using namespace strata;

// n lights on a grid 1.7 m up, every other one a spot aimed down (cones 25 and 45 degrees).
void add_lights(scene::Scene& s, uint32_t n) {
  const uint32_t side = std::max<uint32_t>(1, uint32_t(std::ceil(std::sqrt(double(n)))));
  for (uint32_t i = 0; i < n; ++i) {
    scene::Light l;
    l.name = "lamp" + std::to_string(i);
    l.type = i % 2 == 0 ? scene::LightType::kPoint : scene::LightType::kSpot;
    l.intensity = 2.0f / float(n);
    l.inner_cone = glm::radians(25.0f);
    l.outer_cone = glm::radians(45.0f);
    const float x = -0.8f + 1.6f * (float(i % side) + 0.5f) / float(side);
    const float z = -0.8f + 1.6f * (float(i / side) + 0.5f) / float(side);
    // Local -Z down: a turn of -90 degrees about +X.
    l.transform = glm::rotate(glm::translate(glm::mat4(1.0f), {x, 1.7f, z}), glm::radians(-90.0f), glm::vec3(1, 0, 0));
    s.lights.push_back(l);
  }
}

}  // namespace

int main(int argc, char** argv) {
  CLI::App app("strata_light_bench: frame time with and without punctual lights");
  uint32_t size = 256, frames = 8, lights = 64;
  std::string out = "light_bench.json", device;
  app.add_option("--size", size, "image width and height");
  app.add_option("--frames", frames, "frames per run (the first is not timed)");
  app.add_option("--lights", lights, "punctual lights added");
  app.add_option("--out", out, "JSON output");
  app.add_option("--device", device, "Vulkan device name substring");
  CLI11_PARSE(app, argc, argv);

  gpu::ContextOptions co;
  co.device = device;
  gpu::Context ctx(co);
  nlohmann::json results = nlohmann::json::array();
  for (const std::string method : {"pt", "restir-gather"}) {
    for (uint32_t n : {0u, lights}) {
      scene::Scene s = scene::builtin_scene("cornell");
      add_lights(s, n);
      s.validate();
      render::RenderSettings rs;
      rs.width = size;
      rs.height = size;
      rs.method = method;
      rs.max_depth = 6;
      render::Renderer renderer(ctx, s, rs);
      std::vector<double> ms;
      for (uint32_t f = 0; f < frames; ++f) {
        const auto r = renderer.render(s.frame_state(0), f);
        if (f > 0) ms.push_back(r.stats.gpu_ms_total);
      }
      std::sort(ms.begin(), ms.end());
      const double median = ms.empty() ? 0.0 : ms[ms.size() / 2];
      std::printf("%-14s lights %3u  %dx%d  median frame %.1f ms over %zu frames\n", method.c_str(), n, int(size), int(size),
                  median, ms.size());
      results.push_back({{"method", method}, {"lights", n}, {"size", size}, {"median_gpu_ms", median}, {"frames_ms", ms}});
    }
  }
  std::ofstream(out) << results.dump(2) << "\n";
  return 0;
}
