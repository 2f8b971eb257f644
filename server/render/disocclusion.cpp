#include "render/disocclusion.h"

#include "include/bindings.h"
#include "render/frame_constants.h"

namespace strata::render {

DisocclusionMask::DisocclusionMask(const gpu::Context& ctx, const scene::Scene& scene) : ctx_(ctx), scene_(scene) {
  gpu_scene_ = std::make_unique<GpuScene>(ctx, scene, /*keep_history=*/true);
  auto bindings = GpuScene::bindings(/*with_lights=*/false, /*with_history=*/true);
  bindings.push_back({BINDING_FRAME, VK_DESCRIPTOR_TYPE_UNIFORM_BUFFER});
  bindings.push_back({BINDING_DISOCCLUSION, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER});
  pipeline_ = std::make_unique<gpu::ComputePipeline>(ctx, "disocclusion", bindings, std::vector<gpu::SpecConstant>{}, 0);
  constants_ = gpu::Buffer(ctx, sizeof(gpu::GpuFrameConstants), VK_BUFFER_USAGE_UNIFORM_BUFFER_BIT, gpu::Memory::Host,
                           "disocclusion frame constants");
}

DisocclusionMask::~DisocclusionMask() = default;

std::vector<uint8_t> DisocclusionMask::compute(const scene::FrameState& previous, const scene::FrameState& frame, uint32_t width,
                                               uint32_t height) {
  const size_t pixels = size_t(width) * height;
  gpu::Buffer mask(ctx_, sizeof(uint32_t) * pixels, gpu::k_storage_usage, gpu::Memory::Device, "disocclusion mask");
  gpu::DescriptorSet set(ctx_, *pipeline_);
  ctx_.submit_and_wait([&](VkCommandBuffer cmd) {
    // Two updates in one command buffer: `previous` goes to one slot, `frame` to the other (the
    // second update waits for the first TLAS build; GpuScene records the barriers).
    gpu_scene_->record_update(cmd, previous);
    gpu_scene_->record_update(cmd, frame);
    gpu_scene_->bind(set, /*with_lights=*/false, /*with_history=*/true, gpu_scene_->parity());
    set.bind_buffer(BINDING_FRAME, constants_);
    set.bind_buffer(BINDING_DISOCCLUSION, mask);
    FrameSetup setup;
    setup.width = width;
    setup.height = height;
    gpu::GpuFrameConstants c = make_frame_constants(frame, scene_.environment, *gpu_scene_, setup);
    constants_.upload(&c, sizeof c);
    gpu::dispatch_2d(cmd, *pipeline_, set, width, height);
  });
  auto words = mask.download_as<uint32_t>(pixels);
  return std::vector<uint8_t>(words.begin(), words.end());
}

}  // namespace strata::render
