#pragma once
// Raw ray-query throughput of a scene (pass `ray_throughput`), timed with GPU timestamps: the
// ceiling that the path tracer's achieved rays/s is compared against.
#include <memory>

#include "gpu/pipeline.h"
#include "gpu/timer.h"
#include "render/scene_gpu.h"

namespace strata::render {

struct RayThroughput {
  uint64_t primary_rays = 0;
  uint64_t secondary_rays = 0;
  uint64_t hits = 0;
  double gpu_ms = 0.0;
  double rays_per_second() const { return gpu_ms > 0.0 ? double(primary_rays + secondary_rays) / (gpu_ms * 1e-3) : 0.0; }
};

class RayBenchmark {
 public:
  RayBenchmark(const gpu::Context& ctx, const scene::Scene& scene, uint32_t width, uint32_t height);
  ~RayBenchmark();
  // Traces rays_per_pixel camera rays (and one secondary per primary hit) at `frame`.
  RayThroughput run(const scene::FrameState& frame, uint32_t rays_per_pixel, uint32_t seed);

 private:
  const gpu::Context& ctx_;
  const scene::Scene& scene_;
  uint32_t width_, height_;
  std::unique_ptr<GpuScene> gpu_scene_;
  gpu::Buffer constants_, counters_;
  std::unique_ptr<gpu::ComputePipeline> pipeline_;
  std::unique_ptr<gpu::DescriptorSet> set_;
  std::unique_ptr<gpu::PassTimer> timer_;
};

}  // namespace strata::render
