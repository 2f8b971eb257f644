#include "render/ray_probe.h"

#include "gpu/timer.h"
#include "include/bindings.h"

namespace strata::render {
namespace {

constexpr gpu::Binding k_bindings[] = {
    {BINDING_TLAS, VK_DESCRIPTOR_TYPE_ACCELERATION_STRUCTURE_KHR},
    {BINDING_PROBE_RAYS, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER},
    {BINDING_PROBE_HITS, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER},
};

}  // namespace

RayProbe::RayProbe(const gpu::Context& ctx, const scene::Scene& scene) : ctx_(ctx) {
  gpu_scene_ = std::make_unique<GpuScene>(ctx, scene);
  pipeline_ = std::make_unique<gpu::ComputePipeline>(ctx, "ray_probe", k_bindings, std::span<const gpu::SpecConstant>{},
                                                     uint32_t(sizeof(gpu::GpuDispatchConstants)));
}

RayProbe::~RayProbe() = default;

std::vector<gpu::GpuProbeHit> RayProbe::trace(const scene::FrameState& frame, std::span<const ProbeRay> rays) {
  if (rays.empty()) return {};
  glm::dvec3 origin(frame.camera.position);
  std::vector<gpu::GpuProbeRay> in;
  for (const auto& r : rays) {
    glm::vec3 o(glm::dvec3(r.origin) - origin);
    in.push_back({glm::vec4(o, r.t_min), glm::vec4(r.direction, r.t_max)});
  }
  auto ray_buf = gpu::make_buffer<gpu::GpuProbeRay>(ctx_, in, gpu::k_storage_usage, gpu::Memory::Device, "probe rays");
  gpu::Buffer hit_buf(ctx_, sizeof(gpu::GpuProbeHit) * rays.size(), gpu::k_storage_usage, gpu::Memory::Device, "probe hits");
  gpu::DescriptorSet set(ctx_, *pipeline_);
  set.bind_tlas(BINDING_TLAS, gpu_scene_->tlas().handle());
  set.bind_buffer(BINDING_PROBE_RAYS, ray_buf);
  set.bind_buffer(BINDING_PROBE_HITS, hit_buf);
  ctx_.submit_and_wait([&](VkCommandBuffer cmd) {
    gpu_scene_->record_update(cmd, frame);
    gpu::GpuDispatchConstants d{0, uint32_t(rays.size())};
    gpu::dispatch_1d(cmd, *pipeline_, set, uint32_t(rays.size()), &d, sizeof d);
  });
  return hit_buf.download_as<gpu::GpuProbeHit>(rays.size());
}

}  // namespace strata::render
