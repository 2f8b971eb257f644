#include "service/warm_up.h"

#include <algorithm>
#include <cstdio>
#include <sstream>
#include <stdexcept>

#include "gpu/compiled_pipelines.h"
#include "gpu/pipeline_warmup.h"
#include "render/history_passes.h"
#include "render/method_table.h"
#include "service/options.h"
#include "service/scene_source.h"
#include "service/session_spec.h"

namespace strata::service {
namespace {

constexpr uint32_t k_size = 16;  // pixels a side of the renderers whose pipelines the start-time warm-up records

// The settings a session of `method` at the default options has (as Session builds them).
render::RenderSettings default_settings(const std::string& method, const ServiceLimits& limits) {
  v1::CreateSessionRequest req;
  req.mutable_scene()->set_builtin("carousel");
  req.mutable_resolution()->set_width(k_size);
  req.mutable_resolution()->set_height(k_size);
  req.set_method(method);
  return render_settings(check_create_session(req, limits));
}

double seconds_since(std::chrono::steady_clock::time_point t) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - t).count();
}

}  // namespace

double PipelineCompile::seconds() const { return done() ? seconds_.load() : seconds_since(submitted_); }

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

WarmUp::WarmUp(gpu::ContextOptions device, const ServiceConfig& config, std::vector<std::string> methods, unsigned threads,
               const gpu::Context* service)
    : device_(std::move(device)), threads_(std::max(1u, threads)), service_(service) {
  if (!methods.empty()) {
    v1::SceneSource source;
    source.set_builtin("carousel");
    const std::shared_ptr<const scene::Scene> carousel = load_scene_source(source, config);
    for (const auto& method : methods) jobs_.push_back({carousel, default_settings(method, config.limits), method, nullptr});
    start_jobs_ = int(jobs_.size());
    gpu::warmup_begin();  // /readyz says so from now on
  }
  thread_ = std::thread([this] { run(); });
}

WarmUp::~WarmUp() {
  {
    std::lock_guard lock(mu_);
    stop_ = true;
  }
  cv_.notify_all();
  thread_.join();
  // Jobs never started: their sessions compile at the first dispatch instead.
  for (const auto& job : jobs_)
    if (job.state) job.state->done_ = true;
  if (start_jobs_ > 0) gpu::warmup_end();
}

std::shared_ptr<const PipelineCompile> WarmUp::compile(std::shared_ptr<const scene::Scene> scene, render::RenderSettings settings,
                                                       std::string label) {
  auto state = std::shared_ptr<PipelineCompile>(new PipelineCompile(settings.method));
  {
    std::lock_guard lock(mu_);
    jobs_.push_back({std::move(scene), std::move(settings), std::move(label), state});
  }
  cv_.notify_all();
  return state;
}

bool WarmUp::compiled(const scene::Scene& scene, const render::RenderSettings& settings,
                      std::vector<gpu::PipelineInfo>* pipelines) const {
  try {
    gpu::Context recorder(device_);  // thrown away: its pipelines are layouts only
    auto recorded = gpu::record_pipelines([&] { render::Renderer renderer(recorder, scene, settings); });
    const bool all = gpu::all_compiled(recorded, recorder.device_name());
    if (pipelines) *pipelines = std::move(recorded);
    return all;
  } catch (const std::exception&) {
    return false;
  }
}

void WarmUp::create(const gpu::Context& ctx, const std::vector<gpu::PipelineInfo>& pipelines, const std::string& label) const {
  try {
    const double seconds = gpu::create_pipelines(ctx, pipelines, threads_);
    std::printf("stratad: %s: %zu compiled pipelines created in %.2f s on %u threads\n", label.c_str(), pipelines.size(),
                seconds, threads_);
  } catch (const std::exception& e) {
    std::printf("stratad: %s: creating its pipelines in parallel failed (%s); the renderer creates them\n", label.c_str(), e.what());
  }
  std::fflush(stdout);
}

void WarmUp::run() {
  for (;;) {
    Job job;
    {
      std::unique_lock lock(mu_);
      cv_.wait(lock, [&] { return stop_.load() || !jobs_.empty(); });
      if (stop_.load()) return;
      job = std::move(jobs_.front());
      jobs_.pop_front();
    }
    busy_ = true;
    run_job(job);
    busy_ = false;
    if (job.state) {
      job.state->seconds_ = seconds_since(job.state->submitted_);
      job.state->done_ = true;
    } else {
      std::lock_guard lock(mu_);
      if (--start_jobs_ == 0) gpu::warmup_end();
    }
  }
}

void WarmUp::run_job(const Job& job) {
  const std::string& method = job.settings.method;
  try {
    std::vector<gpu::PipelineInfo> pipelines;
    std::string device_name;
    {
      gpu::Context recorder(device_);  // thrown away: its pipelines are layouts only
      pipelines = gpu::record_pipelines([&] { render::Renderer renderer(recorder, *job.scene, job.settings); });
      device_name = recorder.device_name();
    }
    // A session's job compiles its history passes' pipelines last (render/history_passes.h).
    std::vector<gpu::PipelineInfo> first, history;
    for (const auto& p : pipelines) (job.state && render::history_only_shader(p.shader) ? history : first).push_back(p);
    if (job.state) {
      job.state->pipelines_ = pipelines.size();
      job.state->history_pipelines_ = history.size();
    }
    auto compile = [&](const std::vector<gpu::PipelineInfo>& set) {
      if (set.empty()) return 0.0;
      const double s = gpu::warm_pipelines(device_, set, threads_, stop_, /*readiness=*/!job.state);
      // The service's device keeps them in its pipeline table (gpu::Context::cached_pipeline).
      if (job.state && service_)
        for (const auto& p : set) {
          if (stop_.load()) break;
          gpu::ComputePipeline(*service_, p.shader, p.bindings, p.spec, p.push_constant_bytes);
        }
      if (!stop_.load()) gpu::note_compiled(set, device_name);
      return s;
    };
    double seconds = compile(first);
    if (job.state && !history.empty() && !stop_.load()) {
      job.state->first_seconds_ = job.state->seconds();
      job.state->first_ready_ = true;
      std::printf("stratad: %s: %zu of the %zu pipelines of %s compiled in %.1f s: it renders from its next frame, its history "
                  "passes (%zu pipelines) held until they are compiled\n",
                  job.label.c_str(), first.size(), pipelines.size(), method.c_str(), seconds, history.size());
      std::fflush(stdout);
      seconds += compile(history);
    }
    if (stop_.load()) {
      std::printf("stratad: %s: compiling the pipelines of %s stopped after %.1f s: the service stops\n", job.label.c_str(),
                  method.c_str(), seconds);
    } else if (job.state) {
      std::printf("stratad: %s: the pipelines of %s compiled: %zu in %.1f s on %u threads (%.1f s since it was created)\n",
                  job.label.c_str(), method.c_str(), pipelines.size(), seconds, threads_, job.state->seconds());
    } else {
      std::printf("stratad: pipelines of %s warm: %zu in %.1f s on %u threads (%.1f s since start)\n", method.c_str(),
                  pipelines.size(), seconds, threads_, seconds_since(start_));
    }
  } catch (const std::exception& e) {
    std::printf("stratad: %s: compiling the pipelines of %s stopped: %s (its frames compile them at their first dispatch)\n",
                job.label.c_str(), method.c_str(), e.what());
  }
  std::fflush(stdout);
}

}  // namespace strata::service
