#pragma once
// Traces explicit rays through a scene's acceleration structures (pass `ray_probe`) and returns
// what the ray query reports. Rays are given in world space; the probe uses the frame's render
// space internally. A probe whose scene keeps history can also trace the previous frame's slot.
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

enum class ProbeSlot { current, previous };

class RayProbe {
 public:
  RayProbe(const gpu::Context& ctx, const scene::Scene& scene, bool keep_history = false);
  ~RayProbe();
  // Records the scene update to `frame`, then traces the current slot or (with history) the
  // previous one: the frame state of the call before, in its own render space.
  std::vector<gpu::GpuProbeHit> trace(const scene::FrameState& frame, std::span<const ProbeRay> rays,
                                      ProbeSlot slot = ProbeSlot::current);
  const GpuScene& gpu_scene() const { return *gpu_scene_; }

 private:
  const gpu::Context& ctx_;
  std::unique_ptr<GpuScene> gpu_scene_;
  std::unique_ptr<gpu::ComputePipeline> pipelines_[2];  // by ProbeSlot, made on first use
};

}  // namespace strata::render
