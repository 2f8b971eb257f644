#pragma once
// A stage of a ReSTIR frame (docs/ARCHITECTURE.md): one or more passes over RestirState that a
// method composes (method_table.h). A stage declares its passes (render/pass.h) in its constructor,
// records them into a frame, and says what it did.
#include <cstdint>
#include <map>
#include <span>
#include <string>

#include "gpu/timer.h"
#include "render/frame_stats.h"
#include "render/method.h"
#include "render/method_table.h"

namespace strata::render {

struct RestirState;

// One frame as the stages see it.
struct StageFrame {
  VkCommandBuffer cmd;
  gpu::PassTimer& timer;
  const MethodFrame& frame;
  int parity;  // the scene slot (and ping-pong role) of this frame
};

class Stage {
 public:
  virtual ~Stage() = default;
  // Timed passes it records per frame at most (the renderer's PassTimer is sized by the sum).
  virtual uint32_t timed_passes() const = 0;
  virtual void record(const StageFrame& f) = 0;
  // Whether it ran in the last frame, and which variant or why not (PassDecision of its pass name).
  virtual PassDecision decision() const = 0;
  virtual std::map<std::string, uint64_t> memory_bytes() const { return {}; }
  // Its own counters into the frame statistics.
  virtual void collect(std::span<const uint32_t> counters, FrameStats& stats) const {
    (void)counters;
    (void)stats;
  }
};

// Records `pass` between timer.begin(name) and timer.end, followed by a barrier.
template <class F>
void timed(const StageFrame& f, const char* name, F&& record) {
  f.timer.begin(f.cmd, name);
  record();
  gpu::compute_barrier(f.cmd);
  f.timer.end(f.cmd);
}

}  // namespace strata::render
