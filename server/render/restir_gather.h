#pragma once
// Methods `restir-gather`, `restir-di` (issue 4) and `restir-splat` (issue 5): the passes initial,
// temporal (gather: backprojection; or splatting, render/splat_temporal.h), spatial and shade over per-session reservoir buffers that persist between
// frames. restir-di is the same resampling restricted to one-bounce paths (DESIGN.md section 2).
#include <array>
#include <memory>

#include "render/method.h"
#include "render/renderer.h"
#include "render/splat_temporal.h"

namespace strata::render {

class RestirGather : public Method {
 public:
  RestirGather(const SharedResources& shared, const RenderSettings& settings);
  ~RestirGather() override;
  void record(VkCommandBuffer cmd, gpu::PassTimer& timer, const MethodFrame& f) override;
  std::vector<PassDecision> decisions() const override;
  std::map<std::string, uint64_t> memory_bytes() const override;
  void collect(std::span<const uint32_t> counters, FrameStats& stats) const override;

 private:
  struct Pass;
  const SharedResources shared_;
  RenderSettings settings_;
  gpu::Buffer restir_constants_;
  gpu::Buffer work_;                     // canonical, then temporal output (one reservoir per pixel)
  std::array<gpu::Buffer, 2> history_;   // final reservoirs, ping-pong by frame parity
  gpu::Buffer contribution_;             // f(Y) of the reservoir currently at each pixel, then the
                                         // pixel's directly seen emission (not resampled)
  std::unique_ptr<Pass> initial_, temporal_, spatial_, shade_;
  std::unique_ptr<SplatTemporal> splat_;  // restir-splat: replaces temporal_
  bool ran_temporal_ = false;
  uint32_t partitions_ = 1;  // restir-splat*: K of the last frame
  std::string temporal_reason_;
};

}  // namespace strata::render
