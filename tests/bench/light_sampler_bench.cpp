// strata_light_sampler_bench: the light tree against power selection (light_sampler tree / power)
// in pt at 1 spp on every built-in scene (or --scenes): per pixel the relative variance of M
// independent renders of one frame, var / (mean^2 + 0.01) averaged over pixels and RGB (pt is
// unbiased, so this is its RelMSE at 1 spp; the mean in the denominator is both samplers' 2M
// renders'), and the median frame time; their product is the error at equal time. The samplers
// render in turn, one frame each, so that a changing machine load weighs on both alike. Prints one
// line per scene and writes JSON.
#include <CLI/CLI.hpp>
#include <algorithm>
#include <array>
#include <cstdio>
#include <fstream>
#include <memory>
#include <nlohmann/json.hpp>
#include <sstream>
#include <string>
#include <vector>

#include "gpu/context.h"
#include "render/renderer.h"
#include "scene/scene_io.h"

namespace {

using namespace strata;

struct Run {
  std::vector<double> sum, sum_sq;  // per pixel and RGB over the renders
  std::vector<double> ms;
};

double median(std::vector<double> v) {
  std::sort(v.begin(), v.end());
  return v.empty() ? 0.0 : v[v.size() / 2];
}

}  // namespace

int main(int argc, char** argv) {
  CLI::App app("strata_light_sampler_bench: pt's error and time with the light tree against power selection");
  uint32_t size = 256, renders = 8, frame = 1, max_depth = 6;
  std::string out = "light_sampler_bench.json", device, scenes_arg;
  app.add_option("--size", size, "image width and height");
  app.add_option("--renders", renders, "independent renders per sampler (M)");
  app.add_option("--frame", frame, "animation frame rendered");
  app.add_option("--max-depth", max_depth, "path segments");
  app.add_option("--scenes", scenes_arg, "comma-separated scenes (default: every built-in)");
  app.add_option("--out", out, "JSON output");
  app.add_option("--device", device, "Vulkan device name substring");
  CLI11_PARSE(app, argc, argv);

  std::vector<std::string> scenes;
  if (scenes_arg.empty()) {
    scenes = scene::builtin_scene_names();
  } else {
    std::stringstream ss(scenes_arg);
    for (std::string s; std::getline(ss, s, ',');) scenes.push_back(s);
  }
  gpu::ContextOptions co;
  co.device = device;
  gpu::Context ctx(co);
  nlohmann::json results = nlohmann::json::array();
  for (const std::string& name : scenes) {
    const scene::Scene s = scene::builtin_scene(name);
    const scene::FrameState state = s.frame_state(frame);
    const std::array<render::LightSampler, 2> samplers{render::LightSampler::power, render::LightSampler::tree};
    std::array<Run, 2> runs;
    for (uint32_t r = 0; r <= renders; ++r) {  // render 0 warms up (pipelines, TLAS) and is left out
      for (size_t k = 0; k < 2; ++k) {
        render::RenderSettings rs;
        rs.width = size;
        rs.height = size;
        rs.max_depth = max_depth;
        rs.seed = 7000 + r;
        rs.restir.light_sampler = samplers[k];
        render::Renderer renderer(ctx, s, rs);
        const render::FrameResult f = renderer.render(state, frame);
        if (r == 0) continue;
        Run& run = runs[k];
        run.ms.push_back(f.stats.gpu_ms_total);
        if (run.sum.empty()) run.sum.assign(size_t(size) * size * 3, 0.0), run.sum_sq.assign(size_t(size) * size * 3, 0.0);
        for (size_t p = 0; p < size_t(size) * size; ++p)
          for (size_t c = 0; c < 3; ++c) {
            const double v = f.image.rgba[4 * p + c];
            run.sum[3 * p + c] += v;
            run.sum_sq[3 * p + c] += v * v;
          }
      }
    }
    std::array<double, 2> relvar{};
    const double m = renders;
    for (size_t i = 0; i < runs[0].sum.size(); ++i) {
      const double mean = (runs[0].sum[i] + runs[1].sum[i]) / (2.0 * m);
      for (size_t k = 0; k < 2; ++k) {
        const double var = std::max(0.0, (runs[k].sum_sq[i] - runs[k].sum[i] * runs[k].sum[i] / m) / (m - 1.0));
        relvar[k] += var / (mean * mean + 0.01);
      }
    }
    for (double& v : relvar) v /= double(runs[0].sum.size());
    const double ms_power = median(runs[0].ms), ms_tree = median(runs[1].ms);
    const double error_ratio = relvar[0] > 0.0 ? relvar[1] / relvar[0] : 1.0, time_ratio = ms_tree / ms_power;
    std::printf("%-16s relmse power %.4g tree %.4g (tree/power %.3f)  ms power %.1f tree %.1f (%.3fx)  at equal time %.3f\n",
                name.c_str(), relvar[0], relvar[1], error_ratio, ms_power, ms_tree, time_ratio, error_ratio * time_ratio);
    results.push_back({{"scene", name},
                       {"size", size},
                       {"renders", renders},
                       {"frame", frame},
                       {"relmse_power", relvar[0]},
                       {"relmse_tree", relvar[1]},
                       {"median_ms_power", ms_power},
                       {"median_ms_tree", ms_tree},
                       {"tree_over_power_relmse", error_ratio},
                       {"tree_over_power_ms", time_ratio},
                       {"tree_over_power_equal_time", error_ratio * time_ratio}});
  }
  std::ofstream(out) << results.dump(2) << "\n";
  return 0;
}
