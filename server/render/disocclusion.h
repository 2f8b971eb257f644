#pragma once
// The disocclusion mask of a frame (passes `primary` then `disocclusion`): per pixel, 1 when the
// pixel-centre primary hit of `frame` was not visible from the camera of `previous` (the
// `disoccluded_pixels` statistic). The evaluation restricts its error metrics to these pixels.
#include <cstdint>
#include <memory>
#include <vector>

#include "gpu/buffer.h"
#include "gpu/pipeline.h"
#include "render/pass.h"
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
  void resize(size_t pixels);
  std::unique_ptr<GpuScene> gpu_scene_;
  gpu::Buffer constants_;
  gpu::Buffer visibility_, mask_;  // per pixel: the pixel-centre hit, and the mask word
  size_t pixels_ = 0;
  std::unique_ptr<Pass> primary_, disocclusion_;
};

}  // namespace strata::render
