#pragma once
// Compiling a method's pipelines before a frame dispatches them (gpu/pipeline_warmup.h: lavapipe
// compiles at the first dispatch, one pipeline after another on the device's queue thread), on a
// thread of its own, one job after another, each job on `threads` devices in parallel:
// - `stratad serve --warm-up METHODS`: at start, the pipelines a renderer of each method creates for
//   the built-in carousel at the default options. /readyz answers 503 meanwhile; log lines.
// - The progressive start of a session (`stratad serve`, on by default; service/session.h): the
//   pipelines of the session's own renderer, recorded from its own settings, so that the variants
//   compiled (specialization constants, bindings) are exactly those its frames dispatch and each is
//   compiled once. /readyz is not affected; frames and a log line say it. In two stages: first
//   those a frame without history dispatches, after which the method renders with its history
//   held; then the history passes' (render/history_passes.h: the temporal reuse, the largest
//   shaders), after which its frames reuse history.
// Code compiled here lands in Mesa's disk cache, where the service's device finds it, and is listed
// as compiled (gpu/compiled_pipelines.h): a session whose pipelines are all listed starts with its
// method at once, as its first frame only loads their code. A session's
// job then also creates the pipelines on the service's device (vkCreateComputePipelines: lavapipe
// translates and optimises the SPIR-V there, about 2 s of CPU for restir-gather's), so that the
// frame that takes over finds them in the device's pipeline table and only loads the code.
#include <atomic>
#include <chrono>
#include <condition_variable>
#include <deque>
#include <memory>
#include <mutex>
#include <string>
#include <thread>
#include <vector>

#include "gpu/context.h"
#include "gpu/pipeline_warmup.h"
#include "render/renderer.h"
#include "scene/scene.h"
#include "service/config.h"

namespace strata::service {

// A session's compile job as the session sees it.
class PipelineCompile {
 public:
  bool done() const { return done_.load(); }
  // Whether the pipelines that a frame without history dispatches are compiled: the method can
  // render from now on, its history passes held (render/history_passes.h) until done().
  bool first_frame_ready() const { return first_ready_.load() || done(); }
  // The pipelines recorded (0 until recorded), of them the history passes' (compiled last), and
  // the seconds from submission to done (or so far) and to first_frame_ready.
  size_t pipelines() const { return pipelines_.load(); }
  size_t history_pipelines() const { return history_pipelines_.load(); }
  double seconds() const;
  double first_frame_seconds() const { return first_seconds_.load(); }
  const std::string& method() const { return method_; }

 private:
  friend class WarmUp;
  explicit PipelineCompile(std::string method) : method_(std::move(method)) {}
  const std::string method_;
  const std::chrono::steady_clock::time_point submitted_ = std::chrono::steady_clock::now();
  std::atomic<bool> done_{false};
  std::atomic<bool> first_ready_{false};
  std::atomic<size_t> pipelines_{0};
  std::atomic<size_t> history_pipelines_{0};
  std::atomic<double> seconds_{0.0};
  std::atomic<double> first_seconds_{0.0};
};

class WarmUp {
 public:
  // Starts at once on a thread of its own; `methods` in the order to warm them (unknown names are
  // an std::invalid_argument naming --warm-up); `threads` devices compile in parallel.
  // `service`: the service's device, on which a session's job creates its pipelines after compiling
  // them (null: none).
  WarmUp(gpu::ContextOptions device, const ServiceConfig& config, std::vector<std::string> methods, unsigned threads,
         const gpu::Context* service = nullptr);
  ~WarmUp();  // stops after the pipelines being compiled
  WarmUp(const WarmUp&) = delete;
  WarmUp& operator=(const WarmUp&) = delete;

  // Whether the pipelines a renderer with `settings` creates for `scene` were compiled into Mesa's
  // disk cache before (gpu/compiled_pipelines.h): then its first frame only loads them. Records
  // them on a device of its own (a few hundred ms); false when that fails. `pipelines`, if given,
  // receives them.
  bool compiled(const scene::Scene& scene, const render::RenderSettings& settings,
                std::vector<gpu::PipelineInfo>* pipelines = nullptr) const;

  // Creates compiled `pipelines` on `ctx` on this object's threads at once, so that a renderer then
  // finds them in the device's table instead of creating them one after another; `label` names the
  // log line. A failure is left to the renderer, which creates them itself.
  void create(const gpu::Context& ctx, const std::vector<gpu::PipelineInfo>& pipelines, const std::string& label) const;

  // Whether a job is compiling now (destroying this object waits for the pipelines in progress).
  bool busy() const { return busy_.load(); }

  // Compiles the pipelines a renderer with `settings` creates for `scene`, after the jobs queued
  // before it; `label` names it in the log line. A job that fails marks itself done (the renderer
  // then compiles at its first dispatch, as without it).
  std::shared_ptr<const PipelineCompile> compile(std::shared_ptr<const scene::Scene> scene, render::RenderSettings settings,
                                                 std::string label);

 private:
  struct Job {
    std::shared_ptr<const scene::Scene> scene;
    render::RenderSettings settings;
    std::string label;
    std::shared_ptr<PipelineCompile> state;  // null for the start-time warm-up
  };
  void run();
  void run_job(const Job& job);
  const gpu::ContextOptions device_;
  const unsigned threads_;
  const gpu::Context* const service_;
  const std::chrono::steady_clock::time_point start_ = std::chrono::steady_clock::now();
  std::atomic<bool> stop_{false};
  std::atomic<bool> busy_{false};
  std::mutex mu_;
  std::condition_variable cv_;
  std::deque<Job> jobs_;
  int start_jobs_ = 0;  // start-time jobs not yet done (/readyz is 503 while any is left)
  std::thread thread_;
};

// "restir-gather,pt" or "all" (every available method) or "none": the methods to warm.
std::vector<std::string> parse_warm_up(const std::string& list);

}  // namespace strata::service
