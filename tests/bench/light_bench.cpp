// strata_light_bench: what punctual lights cost. Frame time (median gpu_ms_total of frames 1..F-1)
// of pt and restir-gather on cornell as built and with N punctual lights added (point and spot
// lights spread under the ceiling, all in the light table with the ceiling quad), at 1 spp; the
// configurations take turns frame by frame.
// Prints one line per (method, lights) pair and writes JSON.
#include <CLI/CLI.hpp>
#include <algorithm>
#include <cstdio>
#include <fstream>
#include <memory>
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
  // The four configurations render in turn, one frame each per round, so that a machine whose load
  // changes over the run (a shared CI machine) weighs on all of them alike.
  struct Config {
    std::string method;
    uint32_t lights;
    scene::Scene scene;
    std::unique_ptr<render::Renderer> renderer;
    std::vector<double> ms;
  };
  std::vector<Config> configs;
  for (const std::string method : {"pt", "restir-gather"}) {
    for (uint32_t n : {0u, lights}) {
      Config c{method, n, scene::builtin_scene("cornell"), nullptr, {}};
      add_lights(c.scene, n);
      c.scene.validate();
      configs.push_back(std::move(c));
    }
  }
  for (Config& c : configs) {
    render::RenderSettings rs;
    rs.width = size;
    rs.height = size;
    rs.method = c.method;
    rs.max_depth = 6;
    c.renderer = std::make_unique<render::Renderer>(ctx, c.scene, rs);
    c.renderer->render(c.scene.frame_state(0), 0);  // compiles, builds the TLAS; no history: not timed
  }
  for (uint32_t f = 1; f < frames; ++f)
    for (Config& c : configs) c.ms.push_back(c.renderer->render(c.scene.frame_state(0), f).stats.gpu_ms_total);
  nlohmann::json results = nlohmann::json::array();
  for (Config& c : configs) {
    std::sort(c.ms.begin(), c.ms.end());
    const double median = c.ms.empty() ? 0.0 : c.ms[c.ms.size() / 2];
    std::printf("%-14s lights %3u  %ux%u  median frame %.1f ms over %zu frames\n", c.method.c_str(), c.lights, size, size, median,
                c.ms.size());
    results.push_back({{"method", c.method}, {"lights", c.lights}, {"size", size}, {"median_gpu_ms", median}, {"frames_ms", c.ms}});
  }
  std::ofstream(out) << results.dump(2) << "\n";
  return 0;
}
