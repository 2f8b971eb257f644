#include "render/ray_probe.h"

#include <stdexcept>

#include "gpu/timer.h"
#include "include/bindings.h"

namespace strata::render {
namespace {

// The scene bindings with history (the shader reads the instance records of the slot it traces).
std::vector<gpu::Binding> probe_bindings(const GpuScene& scene) {
  auto b = scene.bindings(/*with_lights=*/false, /*with_history=*/true);
  b.push_back({BINDING_PROBE_RAYS, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER});
  b.push_back({BINDING_PROBE_HITS, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER});
  return b;
}

}  // namespace

RayProbe::RayProbe(const gpu::Context& ctx, const scene::Scene& scene, bool keep_history) : ctx_(ctx) {
  gpu_scene_ = std::make_unique<GpuScene>(ctx, scene, keep_history);
}

RayProbe::~RayProbe() = default;

std::vector<gpu::GpuProbeHit> RayProbe::trace(const scene::FrameState& frame, std::span<const ProbeRay> rays, ProbeSlot slot) {
  if (rays.empty()) return {};
  const bool previous = slot == ProbeSlot::previous;
  if (previous && !gpu_scene_->keeps_history()) throw std::logic_error("RayProbe: the previous slot needs keep_history");
  auto& pipeline = pipelines_[previous ? 1 : 0];
  if (!pipeline) {
    std::vector<gpu::SpecConstant> spec = {{PROBE_SPEC_PREVIOUS, previous ? VK_TRUE : VK_FALSE}};
    gpu_scene_->add_spec(spec);
    pipeline = std::make_unique<gpu::ComputePipeline>(ctx_, gpu_scene_->shader("ray_probe"), probe_bindings(*gpu_scene_), spec,
                                                      uint32_t(sizeof(gpu::GpuDispatchConstants)));
  }
  gpu::Buffer ray_buf(ctx_, sizeof(gpu::GpuProbeRay) * rays.size(), gpu::k_storage_usage, gpu::Memory::Host, "probe rays");
  gpu::Buffer hit_buf(ctx_, sizeof(gpu::GpuProbeHit) * rays.size(), gpu::k_storage_usage, gpu::Memory::Device, "probe hits");
  gpu::DescriptorSet set(ctx_, *pipeline);
  set.bind_buffer(BINDING_PROBE_RAYS, ray_buf);
  set.bind_buffer(BINDING_PROBE_HITS, hit_buf);
  ctx_.submit_and_wait([&](VkCommandBuffer cmd) {
    gpu_scene_->record_update(cmd, frame);
    const int parity = gpu_scene_->parity();
    if (gpu_scene_->keeps_history()) {
      gpu_scene_->bind(set, /*with_lights=*/false, /*with_history=*/true, parity);
    } else {
      // One slot: it stands in for the previous one too, so that the layout is the same.
      gpu_scene_->bind(set, /*with_lights=*/false);
      set.bind_tlas(BINDING_TLAS_PREV, gpu_scene_->tlas().handle());
      set.bind_buffer(BINDING_INSTANCES_PREV, gpu_scene_->instances());
    }
    // World-space rays into the render space of the traced slot's frame (host-visible buffer:
    // written after the update has fixed the slots' origins, before the submission).
    glm::dvec3 origin = gpu_scene_->origin(previous ? 1 - parity : parity);
    std::vector<gpu::GpuProbeRay> in;
    for (const auto& r : rays) {
      glm::vec3 o(glm::dvec3(r.origin) - origin);
      in.push_back({glm::vec4(o, r.t_min), glm::vec4(r.direction, r.t_max)});
    }
    ray_buf.upload(in.data(), in.size() * sizeof(gpu::GpuProbeRay));
    gpu::GpuDispatchConstants d{0, uint32_t(rays.size())};
    gpu::dispatch_1d(cmd, *pipeline, set, uint32_t(rays.size()), &d, sizeof d);
  });
  return hit_buf.download_as<gpu::GpuProbeHit>(rays.size());
}

}  // namespace strata::render
