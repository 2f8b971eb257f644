#include "gpu/pipeline_warmup.h"

#include <algorithm>
#include <chrono>
#include <condition_variable>
#include <exception>
#include <memory>
#include <mutex>
#include <set>
#include <thread>

#include "embedded_shaders.h"

namespace strata::gpu {
namespace {

thread_local std::vector<PipelineInfo>* t_recording = nullptr;
thread_local bool t_warming = false;  // a warm-up worker: never waits for itself

struct WarmupState {
  std::mutex mu;
  std::condition_variable cv;
  std::set<std::string> keys;  // being warmed
  size_t done = 0, total = 0;
  int planned = 0;             // warm-ups between warmup_begin and warmup_end
};

WarmupState& state() {
  static WarmupState s;
  return s;
}

// The longest first (by SPIR-V size, which follows the compile time): the last pipeline to start
// is then a short one, and the threads finish close together.
bool longer_spirv(const PipelineInfo& a, const PipelineInfo& b) {
  return shaders::spirv(a.shader).size() > shaders::spirv(b.shader).size();
}

}  // namespace

std::string PipelineInfo::key() const {
  std::string key = shader + "|push " + std::to_string(push_constant_bytes) + "|bindings";
  for (const auto& b : bindings) key += " " + std::to_string(b.binding) + ":" + std::to_string(int(b.type));
  key += "|spec";
  for (const auto& s : spec) key += " " + std::to_string(s.id) + "=" + std::to_string(s.value);
  return key;
}

bool recording_pipelines() { return t_recording != nullptr; }

std::vector<PipelineInfo> record_pipelines(const std::function<void()>& build) {
  std::vector<PipelineInfo> out;
  t_recording = &out;
  try {
    build();
  } catch (...) {
    t_recording = nullptr;
    throw;
  }
  t_recording = nullptr;
  return out;
}

WarmupProgress warmup_progress() {
  auto& s = state();
  std::lock_guard lock(s.mu);
  return {s.done, s.total, s.planned > 0};
}

void warmup_begin() {
  std::lock_guard lock(state().mu);
  ++state().planned;
}

void warmup_end() {
  std::lock_guard lock(state().mu);
  --state().planned;
}

double warm_pipelines(const ContextOptions& options, const std::vector<PipelineInfo>& pipelines, unsigned threads,
                      const std::atomic<bool>& stop, bool readiness) {
  const auto start = std::chrono::steady_clock::now();
  auto& s = state();
  std::vector<PipelineInfo> todo;
  {
    std::lock_guard lock(s.mu);
    for (const auto& p : pipelines)
      if (s.keys.insert(p.key()).second) todo.push_back(p);
    if (readiness) s.total += todo.size();
  }
  std::stable_sort(todo.begin(), todo.end(), longer_spirv);
  std::atomic<size_t> next{0};
  std::vector<std::thread> workers;
  const unsigned n = std::max(1u, std::min<unsigned>(threads, unsigned(todo.size())));
  for (unsigned w = 0; w < n && !todo.empty(); ++w)
    workers.emplace_back([&] {
      t_warming = true;
      try {
        Context ctx(options);
        for (size_t i; !stop.load() && (i = next.fetch_add(1)) < todo.size();) {
          const auto& p = todo[i];
          ComputePipeline pipeline(ctx, p.shader, p.bindings, p.spec, p.push_constant_bytes);
          ctx.submit_and_wait([&](VkCommandBuffer cmd) {
            vkCmdBindPipeline(cmd, VK_PIPELINE_BIND_POINT_COMPUTE, pipeline.pipeline());
            vkCmdDispatch(cmd, 0, 0, 0);  // compiles; runs nothing
          });
          std::lock_guard lock(state().mu);
          if (readiness) ++state().done;
        }
      } catch (const std::exception&) {
        // A warm-up that fails only costs the first frame its compile time.
      }
    });
  for (auto& t : workers) t.join();  // the devices are gone: Mesa's cache queue has written everything
  {
    std::lock_guard lock(s.mu);
    for (const auto& p : todo) s.keys.erase(p.key());
  }
  s.cv.notify_all();
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

double create_pipelines(const Context& ctx, const std::vector<PipelineInfo>& pipelines, unsigned threads) {
  const auto start = std::chrono::steady_clock::now();
  std::vector<const PipelineInfo*> order;
  for (const auto& p : pipelines) order.push_back(&p);
  std::stable_sort(order.begin(), order.end(), [](const PipelineInfo* a, const PipelineInfo* b) { return longer_spirv(*a, *b); });
  std::atomic<size_t> next{0};
  std::exception_ptr error;
  std::mutex error_mu;
  auto work = [&] {
    for (size_t i; (i = next.fetch_add(1)) < order.size();) {
      const PipelineInfo& p = *order[i];
      try {
        ComputePipeline(ctx, p.shader, p.bindings, p.spec, p.push_constant_bytes);
      } catch (...) {
        std::lock_guard lock(error_mu);
        if (!error) error = std::current_exception();
      }
    }
  };
  std::vector<std::thread> workers;
  const unsigned n = std::max(1u, std::min<unsigned>(threads, unsigned(order.size())));
  for (unsigned w = 1; w < n; ++w) workers.emplace_back(work);
  work();
  for (auto& t : workers) t.join();
  if (error) std::rethrow_exception(error);
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

namespace detail {

bool record_if_recording(const PipelineInfo& info) {
  if (!t_recording) return false;
  const std::string key = info.key();
  if (std::none_of(t_recording->begin(), t_recording->end(), [&](const PipelineInfo& p) { return p.key() == key; }))
    t_recording->push_back(info);
  return true;
}

void wait_if_warming(const std::string& key) {
  if (t_warming) return;
  auto& s = state();
  std::unique_lock lock(s.mu);
  s.cv.wait(lock, [&] { return !s.keys.contains(key); });
}

}  // namespace detail

}  // namespace strata::gpu
