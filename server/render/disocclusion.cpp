#include "render/disocclusion.h"

#include "include/bindings.h"
#include "render/frame_constants.h"
#include "restir/primary_data.h"

namespace strata::render {

DisocclusionMask::DisocclusionMask(const gpu::Context& ctx, const scene::Scene& scene) : ctx_(ctx), scene_(scene) {
  gpu_scene_ = std::make_unique<GpuScene>(ctx, scene, /*keep_history=*/true);
  constants_ = gpu::Buffer(ctx, sizeof(gpu::GpuFrameConstants), VK_BUFFER_USAGE_UNIFORM_BUFFER_BIT, gpu::Memory::Host,
                           "disocclusion frame constants");
  resize(1);
  primary_ = std::make_unique<Pass>(ctx, gpu_scene_.get(), SceneUse{}, "primary",
                                    std::vector<PassResource>{uniform(BINDING_FRAME, constants_),
                                                              storage(BINDING_PRIMARY, Access::write, visibility_)});
  disocclusion_ = std::make_unique<Pass>(ctx, gpu_scene_.get(), SceneUse{.lights = false, .history = true}, "disocclusion",
                                         std::vector<PassResource>{uniform(BINDING_FRAME, constants_),
                                                                   storage(BINDING_PRIMARY, Access::read, visibility_),
                                                                   storage(BINDING_DISOCCLUSION, Access::write, mask_)});
}

DisocclusionMask::~DisocclusionMask() = default;

void DisocclusionMask::resize(size_t pixels) {
  if (pixels == pixels_) return;
  pixels_ = pixels;
  visibility_ = gpu::Buffer(ctx_, sizeof(gpu::GpuPrimaryHit) * pixels, gpu::k_storage_usage, gpu::Memory::Device, "visibility buffer");
  mask_ = gpu::Buffer(ctx_, sizeof(uint32_t) * pixels, gpu::k_storage_usage, gpu::Memory::Device, "disocclusion mask");
  for (Pass* p : {primary_.get(), disocclusion_.get()})
    if (p) p->rebind();
}

std::vector<uint8_t> DisocclusionMask::compute(const scene::FrameState& previous, const scene::FrameState& frame, uint32_t width,
                                               uint32_t height) {
  const size_t pixels = size_t(width) * height;
  resize(pixels);
  ctx_.submit_and_wait([&](VkCommandBuffer cmd) {
    // Two updates in one command buffer: `previous` goes to one slot, `frame` to the other (the
    // second update waits for the first TLAS build; GpuScene records the barriers).
    gpu_scene_->record_update(cmd, previous);
    gpu_scene_->record_update(cmd, frame);
    FrameSetup setup;
    setup.width = width;
    setup.height = height;
    gpu::GpuFrameConstants c = make_frame_constants(frame, scene_.environment, *gpu_scene_, setup);
    constants_.upload(&c, sizeof c);
    const int parity = gpu_scene_->parity();
    primary_->dispatch_2d(cmd, parity, width, height);
    gpu::compute_barrier(cmd);
    disocclusion_->dispatch_2d(cmd, parity, width, height);
  });
  auto words = mask_.download_as<uint32_t>(pixels);
  return std::vector<uint8_t>(words.begin(), words.end());
}

}  // namespace strata::render
