#pragma once
// The disocclusion mask of a frame (pass `disocclusion`): per pixel, 1 when the pixel-centre
// primary hit of `frame` was not visible from the camera of `previous` (DESIGN.md section 4,
// `disoccluded_pixels`). The evaluation restricts its error metrics to these pixels (issue 6).
#include <cstdint>
#include <memory>
#include <vector>

#include "gpu/buffer.h"
#include "gpu/pipeline.h"
#include "render/scene_gpu.h"
#include "scene/scene.h"

namespace strata::render {

class DisocclusionMask {
 public:
  // Uploads the scene with two frame slots; `scene` must outlive this object.
  DisocclusionMask(const gpu::Context& ctx, const scene::Scene& scene);
  ~DisocclusionMask();
  // width * height bytes, row-major from the top row: 1 = disoccluded, 0 = not (or no surface).
  std::vector<uint8_t> compute(const scene::FrameState& previous, const scene::FrameState& frame, uint32_t width,
                               uint32_t height);

 private:
  const gpu::Context& ctx_;
  const scene::Scene& scene_;
  std::unique_ptr<GpuScene> gpu_scene_;
  std::unique_ptr<gpu::ComputePipeline> pipeline_;
  gpu::Buffer constants_;
};

}  // namespace strata::render
