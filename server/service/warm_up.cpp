#include "service/warm_up.h"

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <sstream>
#include <stdexcept>

#include "gpu/pipeline_warmup.h"
#include "render/method_table.h"
#include "render/renderer.h"
#include "service/options.h"
#include "service/scene_source.h"
#include "service/session_spec.h"

namespace strata::service {
namespace {

constexpr uint32_t k_size = 16;  // pixels a side of the renderers whose pipelines are recorded

// The settings a session of `method` at the default options has (as Session builds them).
render::RenderSettings default_settings(const std::string& method, const ServiceLimits& limits) {
  v1::CreateSessionRequest req;
  req.mutable_scene()->set_builtin("carousel");
  req.mutable_resolution()->set_width(k_size);
  req.mutable_resolution()->set_height(k_size);
  req.set_method(method);
  return render_settings(check_create_session(req, limits));
}

}  // namespace

std::vector<std::string> parse_warm_up(const std::string& list) {
  if (list == "none" || list.empty()) return {};
  if (list == "all") return render::available_methods();
  std::vector<std::string> out;
  std::istringstream in(list);
  const auto available = render::available_methods();
  for (std::string m; std::getline(in, m, ',');) {
    if (std::find(available.begin(), available.end(), m) == available.end())
      throw std::invalid_argument("--warm-up: '" + m + "' is not an available method (" + render::method_names() +
                                  "; or all, or none)");
    out.push_back(m);
  }
  return out;
}

WarmUp::WarmUp(gpu::ContextOptions device, const ServiceConfig& config, std::vector<std::string> methods, unsigned threads)
    : device_(std::move(device)), methods_(std::move(methods)), threads_(std::max(1u, threads)) {
  if (methods_.empty()) return;
  gpu::warmup_begin();  // /readyz says so from now on
  thread_ = std::thread([this, config] {
    run(config);
    gpu::warmup_end();
  });
}

WarmUp::~WarmUp() {
  stop_ = true;
  if (thread_.joinable()) thread_.join();
}

void WarmUp::run(const ServiceConfig& config) {
  const auto start = std::chrono::steady_clock::now();
  size_t total = 0;
  try {
    v1::SceneSource source;
    source.set_builtin("carousel");
    const auto scene = load_scene_source(source, config);
    for (const auto& method : methods_) {
      if (stop_.load()) return;
      std::vector<gpu::PipelineInfo> pipelines;
      {
        gpu::Context recorder(device_);  // thrown away: its pipelines are layouts only
        const auto settings = default_settings(method, config.limits);
        pipelines = gpu::record_pipelines([&] { render::Renderer renderer(recorder, *scene, settings); });
      }
      const double seconds = gpu::warm_pipelines(device_, pipelines, threads_, stop_);
      total += pipelines.size();
      std::printf("stratad: pipelines of %s warm: %zu in %.1f s on %u threads (%.1f s since start)\n", method.c_str(),
                  pipelines.size(), seconds, threads_,
                  std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count());
      std::fflush(stdout);
    }
  } catch (const std::exception& e) {
    std::printf("stratad: pipeline warm-up stopped: %s (first frames compile their pipelines instead)\n", e.what());
    std::fflush(stdout);
  }
}

}  // namespace strata::service
