#include "render/ray_benchmark.h"

#include "include/bindings.h"
#include "render/frame_constants.h"

namespace strata::render {

RayBenchmark::RayBenchmark(const gpu::Context& ctx, const scene::Scene& scene, uint32_t width, uint32_t height)
    : ctx_(ctx), scene_(scene), width_(width), height_(height) {
  gpu_scene_ = std::make_unique<GpuScene>(ctx, scene);
  constants_ = gpu::Buffer(ctx, sizeof(gpu::GpuFrameConstants), VK_BUFFER_USAGE_UNIFORM_BUFFER_BIT, gpu::Memory::Host, "frame constants");
  counters_ = gpu::Buffer(ctx, sizeof(uint32_t) * gpu::COUNTER_COUNT, gpu::k_storage_usage, gpu::Memory::Device, "counters");
  auto bindings = gpu_scene_->bindings(/*with_lights=*/false);
  bindings.push_back({BINDING_FRAME, VK_DESCRIPTOR_TYPE_UNIFORM_BUFFER});
  bindings.push_back({BINDING_COUNTERS, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER});
  std::vector<gpu::SpecConstant> spec;
  gpu_scene_->add_spec(spec);
  pipeline_ = std::make_unique<gpu::ComputePipeline>(ctx, gpu_scene_->shader("ray_throughput"), bindings, spec,
                                                     uint32_t(sizeof(gpu::GpuDispatchConstants)));
  set_ = std::make_unique<gpu::DescriptorSet>(ctx, *pipeline_);
  gpu_scene_->bind(*set_, /*with_lights=*/false);
  set_->bind_buffer(BINDING_FRAME, constants_);
  set_->bind_buffer(BINDING_COUNTERS, counters_);
  timer_ = std::make_unique<gpu::PassTimer>(ctx, 2);
}

RayBenchmark::~RayBenchmark() = default;

RayThroughput RayBenchmark::run(const scene::FrameState& frame, uint32_t rays_per_pixel, uint32_t seed) {
  ctx_.submit_and_wait([&](VkCommandBuffer cmd) {
    timer_->reset(cmd);
    gpu_scene_->record_update(cmd, frame);
    vkCmdFillBuffer(cmd, counters_.handle(), 0, VK_WHOLE_SIZE, 0);
    gpu::compute_barrier(cmd);
    FrameSetup setup{width_, height_, 0, seed, rays_per_pixel, 1, false};
    gpu::GpuFrameConstants c = make_frame_constants(frame, scene_.environment, *gpu_scene_, setup);
    constants_.upload(&c, sizeof c);
    gpu::GpuDispatchConstants d{0, rays_per_pixel};
    timer_->begin(cmd, "ray_throughput");
    gpu::dispatch_2d(cmd, *pipeline_, *set_, width_, height_, &d, sizeof d);
    timer_->end(cmd);
  });
  auto counters = counters_.download_as<uint32_t>(gpu::COUNTER_COUNT);
  RayThroughput r;
  r.primary_rays = counters[0];
  r.secondary_rays = counters[1];
  r.hits = counters[2];
  for (const auto& p : timer_->read()) r.gpu_ms += p.ms;
  return r;
}

}  // namespace strata::render
