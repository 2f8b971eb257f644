#pragma once
// Compiling compute pipelines before the first frame needs them. lavapipe (llvmpipe) builds a
// pipeline's machine code at its first dispatch, not at vkCreateComputePipelines, one pipeline
// after another on the device's single queue thread: that is what a cold machine's first frame
// waits for (Mesa's disk cache, $MESA_SHADER_CACHE_DIR, keeps the code for later starts). A dispatch
// of zero workgroups compiles too, and needs no resources bound.
//
// The warm-up records which pipelines a renderer creates (record_pipelines: layouts only, nothing
// compiled), then `threads` devices of their own each create a share of them and dispatch zero
// workgroups, in parallel; the code lands in Mesa's disk cache, where every other device of the
// process (the service's) and the next start find it. Meanwhile a ComputePipeline whose key is
// being warmed waits for the warm-up rather than compiling the same code alongside it.
#include <atomic>
#include <cstdint>
#include <functional>
#include <string>
#include <vector>

#include "gpu/context.h"
#include "gpu/pipeline.h"

namespace strata::gpu {

struct PipelineInfo {
  std::string shader;
  std::vector<Binding> bindings;
  std::vector<SpecConstant> spec;
  uint32_t push_constant_bytes = 0;
  // What tells pipelines apart (Context::cached_pipeline's key).
  std::string key() const;
};

// The pipelines `build` creates on this thread (each once, in order of creation). While it runs,
// ComputePipeline makes layouts only (no VkPipeline): run it on a context of its own, thrown away after.
std::vector<PipelineInfo> record_pipelines(const std::function<void()>& build);
// Whether record_pipelines is running on this thread. Nothing can be dispatched then (its pipelines
// have no VkPipeline): a renderer that would measure its scene on the device while being built
// (restir-multilayer's layer count) takes a stand-in value that creates the same pipelines.
bool recording_pipelines();

struct WarmupProgress {
  size_t done = 0, total = 0;
  bool running = false;  // between warmup_begin and warmup_end
};
WarmupProgress warmup_progress();
// A warm-up about to record and compile (running from begin to end, as warmup_progress says).
void warmup_begin();
void warmup_end();

// Compiles `pipelines` on min(threads, pipelines) devices chosen by `options`, in parallel, and
// returns when every one is in Mesa's disk cache (the devices are destroyed, which flushes it).
// `stop` ends it early (after the pipelines in progress). The longest (by SPIR-V size) start first.
// With `readiness` they count in warmup_progress (a start-time warm-up, which /readyz reports); a
// session's compile does not. Returns the seconds it took.
double warm_pipelines(const ContextOptions& options, const std::vector<PipelineInfo>& pipelines, unsigned threads,
                      const std::atomic<bool>& stop, bool readiness = true);

// Creates `pipelines` on `ctx` (into its pipeline table, Context::cached_pipeline) with up to
// `threads` threads at once, and returns the seconds it took. On a warm cache this is most of a
// session's start: vkCreateComputePipelines translates and lowers each shader (lavapipe: a few
// hundred ms for a ReSTIR pass), while the machine code comes from Mesa's cache at the first dispatch.
double create_pipelines(const Context& ctx, const std::vector<PipelineInfo>& pipelines, unsigned threads);

namespace detail {
// For ComputePipeline: whether record_pipelines is running on this thread (then it records `info`).
bool record_if_recording(const PipelineInfo& info);
// For ComputePipeline: waits while `key` is being warmed (unless this thread is a warm-up's).
void wait_if_warming(const std::string& key);
}  // namespace detail

}  // namespace strata::gpu
