#include "gpu/pipeline.h"

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <map>
#include <stdexcept>

#include "embedded_shaders.h"
#include "gpu/pipeline_warmup.h"

namespace strata::gpu {

ComputePipeline::ComputePipeline(const Context& ctx, std::string shader, std::span<const Binding> bindings,
                                 std::span<const SpecConstant> spec, uint32_t push_constant_bytes)
    : name_(std::move(shader)), bindings_(bindings.begin(), bindings.end()) {
  const PipelineInfo info{name_, bindings_, {spec.begin(), spec.end()}, push_constant_bytes};
  key_ = info.key();
  // Recording what a renderer needs (gpu/pipeline_warmup.h): layouts only, no compile. Creating
  // does not wait for a warm-up of the same key: lavapipe compiles at the first dispatch, which
  // waits (wait_if_warming), so that a renderer can be made while some of its pipelines still warm.
  const bool record_only = detail::record_if_recording(info);
  objects_ = std::static_pointer_cast<Objects>(ctx.cached_pipeline(key_, [&]() -> std::shared_ptr<void> {
    auto o = std::make_shared<Objects>();
    o->device = ctx.device();
    std::vector<VkDescriptorSetLayoutBinding> lb;
    for (const auto& b : bindings_) lb.push_back({b.binding, b.type, 1, VK_SHADER_STAGE_COMPUTE_BIT, nullptr});
    VkDescriptorSetLayoutCreateInfo lci{VK_STRUCTURE_TYPE_DESCRIPTOR_SET_LAYOUT_CREATE_INFO};
    lci.bindingCount = uint32_t(lb.size());
    lci.pBindings = lb.data();
    check(vkCreateDescriptorSetLayout(ctx.device(), &lci, nullptr, &o->set_layout), "vkCreateDescriptorSetLayout");
    VkPipelineLayoutCreateInfo pli{VK_STRUCTURE_TYPE_PIPELINE_LAYOUT_CREATE_INFO};
    pli.setLayoutCount = 1;
    pli.pSetLayouts = &o->set_layout;
    VkPushConstantRange pcr{VK_SHADER_STAGE_COMPUTE_BIT, 0, push_constant_bytes};
    if (push_constant_bytes > 0) {
      pli.pushConstantRangeCount = 1;
      pli.pPushConstantRanges = &pcr;
    }
    check(vkCreatePipelineLayout(ctx.device(), &pli, nullptr, &o->layout), "vkCreatePipelineLayout");
    if (record_only) return o;

    auto words = shaders::spirv(name_);
    VkShaderModuleCreateInfo smci{VK_STRUCTURE_TYPE_SHADER_MODULE_CREATE_INFO};
    smci.codeSize = words.size_bytes();
    smci.pCode = words.data();
    VkShaderModule module;
    check(vkCreateShaderModule(ctx.device(), &smci, nullptr, &module), "vkCreateShaderModule");

    std::vector<VkSpecializationMapEntry> entries;
    std::vector<uint32_t> values;
    for (const auto& s : spec) {
      entries.push_back({s.id, uint32_t(values.size() * sizeof(uint32_t)), sizeof(uint32_t)});
      values.push_back(s.value);
    }
    VkSpecializationInfo si{uint32_t(entries.size()), entries.data(), values.size() * sizeof(uint32_t), values.data()};
    VkComputePipelineCreateInfo ci{VK_STRUCTURE_TYPE_COMPUTE_PIPELINE_CREATE_INFO};
    ci.stage.sType = VK_STRUCTURE_TYPE_PIPELINE_SHADER_STAGE_CREATE_INFO;
    ci.stage.stage = VK_SHADER_STAGE_COMPUTE_BIT;
    ci.stage.module = module;
    ci.stage.pName = "main";
    ci.stage.pSpecializationInfo = entries.empty() ? nullptr : &si;
    ci.layout = o->layout;
    const auto start = std::chrono::steady_clock::now();
    VkResult r = vkCreateComputePipelines(ctx.device(), VK_NULL_HANDLE, 1, &ci, nullptr, &o->pipeline);
    // STRATA_LOG_PIPELINES=1: each compile with its time (what a cold shader cache costs, per variant).
    static const bool log = std::getenv("STRATA_LOG_PIPELINES") != nullptr;
    if (log)
      std::fprintf(stderr, "pipeline %8.1f ms  %s\n",
                   std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count(), key_.c_str());
    vkDestroyShaderModule(ctx.device(), module, nullptr);
    check(r, ("vkCreateComputePipelines(" + name_ + ")").c_str());
    return o;
  }));
}

ComputePipeline::~ComputePipeline() = default;

ComputePipeline::Objects::~Objects() {
  if (!device) return;
  vkDestroyPipeline(device, pipeline, nullptr);
  vkDestroyPipelineLayout(device, layout, nullptr);
  vkDestroyDescriptorSetLayout(device, set_layout, nullptr);
}

DescriptorSet::DescriptorSet(const Context& ctx, const ComputePipeline& pipeline)
    : ctx_(ctx), bindings_(pipeline.bindings()) {
  std::map<VkDescriptorType, uint32_t> counts;
  for (const auto& b : bindings_) counts[b.type]++;
  std::vector<VkDescriptorPoolSize> sizes;
  for (auto [type, n] : counts) sizes.push_back({type, n});
  VkDescriptorPoolCreateInfo pci{VK_STRUCTURE_TYPE_DESCRIPTOR_POOL_CREATE_INFO};
  pci.maxSets = 1;
  pci.poolSizeCount = uint32_t(sizes.size());
  pci.pPoolSizes = sizes.data();
  check(vkCreateDescriptorPool(ctx.device(), &pci, nullptr, &pool_), "vkCreateDescriptorPool");
  VkDescriptorSetLayout layout = pipeline.set_layout();
  VkDescriptorSetAllocateInfo ai{VK_STRUCTURE_TYPE_DESCRIPTOR_SET_ALLOCATE_INFO};
  ai.descriptorPool = pool_;
  ai.descriptorSetCount = 1;
  ai.pSetLayouts = &layout;
  check(vkAllocateDescriptorSets(ctx.device(), &ai, &set_), "vkAllocateDescriptorSets");
}

DescriptorSet::~DescriptorSet() { vkDestroyDescriptorPool(ctx_.device(), pool_, nullptr); }

VkDescriptorType DescriptorSet::type_of(uint32_t binding) const {
  auto it = std::find_if(bindings_.begin(), bindings_.end(), [&](const Binding& b) { return b.binding == binding; });
  if (it == bindings_.end()) throw GpuError("descriptor binding " + std::to_string(binding) + " is not in the layout");
  return it->type;
}

void DescriptorSet::bind_buffer(uint32_t binding, const Buffer& buffer) {
  VkDescriptorBufferInfo info{buffer.handle(), 0, VK_WHOLE_SIZE};
  VkWriteDescriptorSet w{VK_STRUCTURE_TYPE_WRITE_DESCRIPTOR_SET};
  w.dstSet = set_;
  w.dstBinding = binding;
  w.descriptorCount = 1;
  w.descriptorType = type_of(binding);
  w.pBufferInfo = &info;
  vkUpdateDescriptorSets(ctx_.device(), 1, &w, 0, nullptr);
}

void DescriptorSet::bind_tlas(uint32_t binding, VkAccelerationStructureKHR tlas) {
  VkWriteDescriptorSetAccelerationStructureKHR as{VK_STRUCTURE_TYPE_WRITE_DESCRIPTOR_SET_ACCELERATION_STRUCTURE_KHR};
  as.accelerationStructureCount = 1;
  as.pAccelerationStructures = &tlas;
  VkWriteDescriptorSet w{VK_STRUCTURE_TYPE_WRITE_DESCRIPTOR_SET, &as};
  w.dstSet = set_;
  w.dstBinding = binding;
  w.descriptorCount = 1;
  w.descriptorType = type_of(binding);
  vkUpdateDescriptorSets(ctx_.device(), 1, &w, 0, nullptr);
}

void ComputePipeline::wait_if_warming() const {
  if (warm_checked_.load(std::memory_order_acquire)) return;
  detail::wait_if_warming(key_);
  warm_checked_.store(true, std::memory_order_release);
}

namespace {
void bind(VkCommandBuffer cmd, const ComputePipeline& p, const DescriptorSet& set, const void* push_constants,
          uint32_t push_bytes) {
  p.wait_if_warming();
  // A pipeline made while record_pipelines ran has a layout only: binding it would hand the driver
  // a null pipeline (lavapipe crashes on its queue thread).
  if (p.pipeline() == VK_NULL_HANDLE)
    throw std::logic_error("pipeline " + p.name() + " was only recorded, not created: it cannot be dispatched");
  vkCmdBindPipeline(cmd, VK_PIPELINE_BIND_POINT_COMPUTE, p.pipeline());
  if (push_bytes > 0) vkCmdPushConstants(cmd, p.layout(), VK_SHADER_STAGE_COMPUTE_BIT, 0, push_bytes, push_constants);
  VkDescriptorSet s = set.handle();
  vkCmdBindDescriptorSets(cmd, VK_PIPELINE_BIND_POINT_COMPUTE, p.layout(), 0, 1, &s, 0, nullptr);
}
}  // namespace

void dispatch_2d(VkCommandBuffer cmd, const ComputePipeline& p, const DescriptorSet& set, uint32_t width, uint32_t height,
                 const void* push_constants, uint32_t push_bytes) {
  bind(cmd, p, set, push_constants, push_bytes);
  vkCmdDispatch(cmd, (width + 7) / 8, (height + 7) / 8, 1);
}

void dispatch_layers(VkCommandBuffer cmd, const ComputePipeline& p, const DescriptorSet& set, uint32_t width, uint32_t height,
                     uint32_t layers) {
  bind(cmd, p, set, nullptr, 0);
  vkCmdDispatch(cmd, (width + 7) / 8, (height + 7) / 8, layers);
}

void dispatch_1d(VkCommandBuffer cmd, const ComputePipeline& p, const DescriptorSet& set, uint32_t count,
                 const void* push_constants, uint32_t push_bytes) {
  bind(cmd, p, set, push_constants, push_bytes);
  vkCmdDispatch(cmd, (count + 63) / 64, 1, 1);
}

void dispatch_indirect(VkCommandBuffer cmd, const ComputePipeline& p, const DescriptorSet& set, const Buffer& args,
                       VkDeviceSize offset, const void* push_constants, uint32_t push_bytes) {
  bind(cmd, p, set, push_constants, push_bytes);
  vkCmdDispatchIndirect(cmd, args.handle(), offset);
}

void compute_barrier(VkCommandBuffer cmd) {
  VkMemoryBarrier2 mb{VK_STRUCTURE_TYPE_MEMORY_BARRIER_2};
  mb.srcStageMask = VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT | VK_PIPELINE_STAGE_2_TRANSFER_BIT;
  mb.srcAccessMask = VK_ACCESS_2_SHADER_WRITE_BIT | VK_ACCESS_2_TRANSFER_WRITE_BIT;
  mb.dstStageMask = VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT | VK_PIPELINE_STAGE_2_TRANSFER_BIT | VK_PIPELINE_STAGE_2_DRAW_INDIRECT_BIT;
  mb.dstAccessMask = VK_ACCESS_2_SHADER_READ_BIT | VK_ACCESS_2_SHADER_WRITE_BIT | VK_ACCESS_2_TRANSFER_READ_BIT |
                     VK_ACCESS_2_TRANSFER_WRITE_BIT | VK_ACCESS_2_INDIRECT_COMMAND_READ_BIT;
  VkDependencyInfo dep{VK_STRUCTURE_TYPE_DEPENDENCY_INFO};
  dep.memoryBarrierCount = 1;
  dep.pMemoryBarriers = &mb;
  vkCmdPipelineBarrier2(cmd, &dep);
}

}  // namespace strata::gpu
