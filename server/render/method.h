#pragma once
// A rendering method records its passes into a frame after the scene update. The Renderer owns
// what every method shares (the scene on the device, frame constants, counters, the radiance
// accumulation buffer, the pass timer); a method owns its pipelines and per-session state, and
// allocates nothing that it does not use (docs/ARCHITECTURE.md).
#include <cstdint>
#include <map>
#include <memory>
#include <optional>
#include <span>
#include <string>
#include <vector>

#include "gpu/pipeline.h"
#include "gpu/timer.h"
#include "render/frame_stats.h"
#include "render/restir/domain_map.h"
#include "render/scene_gpu.h"

namespace strata::render {

struct RenderSettings;

// Resources the Renderer owns and every method binds.
struct SharedResources {
  const gpu::Context& ctx;
  const GpuScene& scene;
  const gpu::Buffer& constants;  // GpuFrameConstants (uniform)
  const gpu::Buffer& counters;   // COUNTER_* slots
  const gpu::Buffer& accum;      // per pixel: rgb radiance sum, a = sample count
};

struct MethodFrame {
  const scene::FrameState& frame;
  uint32_t frame_index;
  uint64_t sample_base;  // samples already accumulated for this frame state
  bool env_nee;          // the environment is sampled by next-event estimation
  bool history_valid;    // the scene's previous slot holds the previous frame (GpuScene::history_valid), and the
                         // history passes may run (false while held: Renderer::hold_history)
  bool history_held;     // history_valid is false because the history passes wait for their pipelines
  bool scene_moved;      // some transform, LoD level or punctual light changed since the previous frame
};

class Method {
 public:
  virtual ~Method() = default;
  // Timed passes (PassTimer begin/end pairs) it records per frame at most.
  virtual uint32_t timed_passes() const = 0;
  // Records this frame's passes, each inside timer.begin/end, adding radiance to `accum`.
  virtual void record(VkCommandBuffer cmd, gpu::PassTimer& timer, const MethodFrame& f) = 0;
  // Which passes ran in the last recorded frame, and why others did not.
  virtual std::vector<PassDecision> decisions() const = 0;
  // Device memory the method itself holds, by buffer group.
  virtual std::map<std::string, uint64_t> memory_bytes() const = 0;
  // Whether its domains start at the visibility buffer's camera samples (GpuFrameConstants::primary_mode).
  virtual bool fixed_primary() const { return false; }
  // The last frame's domain map (render/restir/domain_map.h); none without pixel layers.
  virtual std::optional<DomainMap> domain_map() const { return std::nullopt; }
  // Adds the method's own counters (frame_data.h COUNTER_*) to the frame statistics.
  virtual void collect(std::span<const uint32_t> counters, FrameStats& stats) const {
    (void)counters;
    (void)stats;
  }
};

// The implementation of settings.method's row of the method table (method_table.h).
std::unique_ptr<Method> make_method(const RenderSettings& settings, const SharedResources& shared);

}  // namespace strata::render
