// `stratad bench`: raw ray-query throughput per scene next to the path tracer's achieved rays/s,
// measured in the same run on the same device (GPU timestamps, after a warm-up that lets lavapipe
// compile its shaders). Writes JSON and prints a Markdown table for docs/BENCHMARKS.md.
#include <algorithm>
#include <cstdio>
#include <fstream>
#include <iostream>
#include <nlohmann/json.hpp>
#include <sstream>

#include "cli/commands.h"
#include "util/summary.h"
#include "gpu/context.h"
#include "render/ray_benchmark.h"
#include "render/renderer.h"
#include "scene/scene_io.h"

namespace strata::cli {
namespace {

struct BenchArgs {
  std::string scenes = "all";
  uint32_t width = 128, height = 128;
  uint32_t rays_per_pixel = 8;
  uint32_t spp = 4;
  uint32_t repeats = 3;
  std::string out = "bench.json";
  std::string device;
};

std::vector<std::string> split(const std::string& s) {
  std::vector<std::string> out;
  std::stringstream ss(s);
  for (std::string item; std::getline(ss, item, ',');)
    if (!item.empty()) out.push_back(item);
  return out;
}

double median(std::vector<double> v) { return util::summarize(std::move(v)).p50; }

int run_bench(const BenchArgs& a) {
  gpu::Context ctx({a.device, false});
  auto names = a.scenes == "all" ? scene::builtin_scene_names() : split(a.scenes);
  nlohmann::json doc;
  doc["device"] = ctx.device_name();
  doc["width"] = a.width;
  doc["height"] = a.height;
  doc["rays_per_pixel"] = a.rays_per_pixel;
  doc["spp"] = a.spp;
  doc["scenes"] = nlohmann::json::array();
  std::printf("| scene | triangles | ray query Mrays/s | path tracer Mrays/s | ratio | pt ms/frame |\n");
  std::printf("|---|---:|---:|---:|---:|---:|\n");
  for (const auto& name : names) {
    scene::Scene s = scene::load_scene(name);
    scene::FrameState frame = s.frame_state(0);
    render::RayBenchmark rb(ctx, s, a.width, a.height);
    rb.run(frame, 1, 0);  // warm-up
    std::vector<double> ray_rates;
    render::RayThroughput last;
    for (uint32_t i = 0; i < a.repeats; ++i) {
      last = rb.run(frame, a.rays_per_pixel, i + 1);
      ray_rates.push_back(last.rays_per_second());
    }
    render::RenderSettings rs;
    rs.width = a.width;
    rs.height = a.height;
    rs.spp = a.spp;
    render::Renderer renderer(ctx, s, rs);
    renderer.render(frame, 0);  // warm-up
    std::vector<double> pt_rates, pt_ms;
    for (uint32_t i = 0; i < a.repeats; ++i) {
      auto r = renderer.render(frame, i + 1);
      double ms = 0.0;
      for (const auto& p : r.stats.pass_ms)
        if (p.pass == "path_trace") ms = p.ms;
      pt_rates.push_back(double(r.stats.rays_total()) / (ms * 1e-3));
      pt_ms.push_back(r.stats.gpu_ms_total);
    }
    double rq = median(ray_rates), pt = median(pt_rates);
    std::printf("| %s | %zu | %.2f | %.2f | %.2f | %.1f |\n", name.c_str(), s.triangle_count(), rq * 1e-6, pt * 1e-6, pt / rq,
                median(pt_ms));
    std::fflush(stdout);
    doc["scenes"].push_back({{"scene", name},
                             {"triangles", s.triangle_count()},
                             {"ray_query_rays_per_s", rq},
                             {"ray_query_hit_fraction", double(last.hits) / double(last.primary_rays + last.secondary_rays)},
                             {"path_tracer_rays_per_s", pt},
                             {"path_tracer_to_ray_query_ratio", pt / rq},
                             {"path_tracer_frame_ms", median(pt_ms)}});
  }
  std::ofstream(a.out) << doc.dump(2) << "\n";
  std::cerr << "wrote " << a.out << "\n";
  return 0;
}

}  // namespace

Runner add_bench_command(CLI::App& app) {
  auto a = std::make_shared<BenchArgs>();
  auto* cmd = app.add_subcommand("bench", "ray-query throughput vs the path tracer's rays/s, per scene");
  cmd->add_option("--scenes", a->scenes, "comma-separated scene names, or 'all'")->capture_default_str();
  cmd->add_option("--width", a->width)->capture_default_str();
  cmd->add_option("--height", a->height)->capture_default_str();
  cmd->add_option("--rays-per-pixel", a->rays_per_pixel, "camera rays per pixel for the raw measurement")->capture_default_str();
  cmd->add_option("--spp", a->spp, "path tracer samples per pixel per frame")->capture_default_str();
  cmd->add_option("--repeats", a->repeats, "timed repetitions (median reported)")->capture_default_str();
  cmd->add_option("--out", a->out, "JSON output path")->capture_default_str();
  cmd->add_option("--device", a->device, "Vulkan device name substring");
  return [a] { return run_bench(*a); };
}

}  // namespace strata::cli
