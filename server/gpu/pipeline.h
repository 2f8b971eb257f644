#pragma once
// Compute pipelines from the SPIR-V compiled in at build time, with specialization constants,
// and the descriptor sets that feed them.
#include <atomic>
#include <cstdint>
#include <memory>
#include <span>
#include <string>
#include <vector>

#include "gpu/buffer.h"

namespace strata::gpu {

struct Binding {
  uint32_t binding;
  VkDescriptorType type;
};

struct SpecConstant {
  uint32_t id;
  uint32_t value;  // booleans as VK_TRUE / VK_FALSE
};

class ComputePipeline {
 public:
  ComputePipeline(const Context& ctx, std::string shader, std::span<const Binding> bindings,
                  std::span<const SpecConstant> spec = {}, uint32_t push_constant_bytes = 0);
  ~ComputePipeline();
  ComputePipeline(const ComputePipeline&) = delete;
  ComputePipeline& operator=(const ComputePipeline&) = delete;

  VkPipeline pipeline() const { return objects_->pipeline; }
  VkPipelineLayout layout() const { return objects_->layout; }
  VkDescriptorSetLayout set_layout() const { return objects_->set_layout; }
  const std::string& name() const { return name_; }
  const std::vector<Binding>& bindings() const { return bindings_; }
  // Before its first dispatch: waits while a warm-up compiles its code (gpu/pipeline_warmup.h), so
  // that the dispatch loads that code from Mesa's cache instead of compiling it alongside.
  void wait_if_warming() const;

 private:
  // The Vulkan objects, shared through the context's pipeline cache (Context::cached_pipeline).
  struct Objects {
    VkDevice device = VK_NULL_HANDLE;
    VkDescriptorSetLayout set_layout = VK_NULL_HANDLE;
    VkPipelineLayout layout = VK_NULL_HANDLE;
    VkPipeline pipeline = VK_NULL_HANDLE;
    ~Objects();
  };
  std::string name_;
  std::string key_;  // PipelineInfo::key
  std::vector<Binding> bindings_;
  std::shared_ptr<Objects> objects_;
  mutable std::atomic<bool> warm_checked_{false};
};

// One descriptor set for one pipeline, in its own small pool.
class DescriptorSet {
 public:
  DescriptorSet(const Context& ctx, const ComputePipeline& pipeline);
  ~DescriptorSet();
  DescriptorSet(const DescriptorSet&) = delete;
  DescriptorSet& operator=(const DescriptorSet&) = delete;

  void bind_buffer(uint32_t binding, const Buffer& buffer);
  void bind_tlas(uint32_t binding, VkAccelerationStructureKHR tlas);
  VkDescriptorSet handle() const { return set_; }

 private:
  VkDescriptorType type_of(uint32_t binding) const;
  const Context& ctx_;
  std::vector<Binding> bindings_;
  VkDescriptorPool pool_ = VK_NULL_HANDLE;
  VkDescriptorSet set_ = VK_NULL_HANDLE;
};

// Binds pipeline and set (and push constants, if any), then dispatches enough 8x8 groups to cover
// width x height.
void dispatch_2d(VkCommandBuffer cmd, const ComputePipeline& p, const DescriptorSet& set, uint32_t width, uint32_t height,
                 const void* push_constants = nullptr, uint32_t push_bytes = 0);

// The same with `layers` workgroups along z (gl_GlobalInvocationID.z = layer, local_size_z = 1).
void dispatch_layers(VkCommandBuffer cmd, const ComputePipeline& p, const DescriptorSet& set, uint32_t width, uint32_t height,
                     uint32_t layers);

// The same for a 1D pass with 64-wide workgroups covering `count` items.
void dispatch_1d(VkCommandBuffer cmd, const ComputePipeline& p, const DescriptorSet& set, uint32_t count,
                 const void* push_constants = nullptr, uint32_t push_bytes = 0);

// The same with the workgroup counts read from `args` at `offset` (a VkDispatchIndirectCommand an
// earlier pass wrote; `args` needs k_indirect_usage).
void dispatch_indirect(VkCommandBuffer cmd, const ComputePipeline& p, const DescriptorSet& set, const Buffer& args,
                       VkDeviceSize offset = 0, const void* push_constants = nullptr, uint32_t push_bytes = 0);

// Full compute-to-compute/transfer barrier between passes (also makes indirect arguments written
// by a pass visible to a later dispatch_indirect).
void compute_barrier(VkCommandBuffer cmd);

}  // namespace strata::gpu
