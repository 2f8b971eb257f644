#pragma once
// Traces explicit rays through a scene's acceleration structures (pass `ray_probe`) and returns
// what the ray query reports. Rays are given in world space; the probe uses the frame's render
// space internally.
#include <memory>
#include <span>
#include <vector>

#include "gpu/pipeline.h"
#include "include/probe_data.h"
#include "render/scene_gpu.h"

namespace strata::render {

struct ProbeRay {
  glm::vec3 origin;  // world space
  glm::vec3 direction;
  float t_min = 0.0f;
  float t_max = 1e30f;
};

class RayProbe {
 public:
  RayProbe(const gpu::Context& ctx, const scene::Scene& scene);
  ~RayProbe();
  std::vector<gpu::GpuProbeHit> trace(const scene::FrameState& frame, std::span<const ProbeRay> rays);

 private:
  const gpu::Context& ctx_;
  std::unique_ptr<GpuScene> gpu_scene_;
  std::unique_ptr<gpu::ComputePipeline> pipeline_;
};

}  // namespace strata::render
