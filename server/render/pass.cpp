#include "render/pass.h"

#include "include/bindings.h"

namespace strata::render {
namespace {

constexpr VkDescriptorType k_storage = VK_DESCRIPTOR_TYPE_STORAGE_BUFFER;

}  // namespace

gpu::Buffer device_storage(const gpu::Context& ctx, size_t bytes, const std::string& name) {
  return gpu::Buffer(ctx, bytes, gpu::k_storage_usage, gpu::Memory::Device, name.c_str());
}

PingPong::PingPong(const gpu::Context& ctx, size_t bytes, const std::string& name, VkBufferUsageFlags usage) {
  for (auto& s : slots_) s = gpu::Buffer(ctx, bytes, usage, gpu::Memory::Device, name.c_str());
}

PassResource uniform(uint32_t binding, const gpu::Buffer& buffer) {
  return {binding, VK_DESCRIPTOR_TYPE_UNIFORM_BUFFER, Access::read, [&buffer](int) -> const gpu::Buffer& { return buffer; }};
}

PassResource storage(uint32_t binding, Access access, const gpu::Buffer& buffer) {
  return {binding, k_storage, access, [&buffer](int) -> const gpu::Buffer& { return buffer; }};
}

PassResource history_current(uint32_t binding, Access access, const PingPong& history) {
  return {binding, k_storage, access, [&history](int parity) -> const gpu::Buffer& { return history.current(parity); }};
}

PassResource history_previous(uint32_t binding, const PingPong& history) {
  return {binding, k_storage, Access::read, [&history](int parity) -> const gpu::Buffer& { return history.previous(parity); }};
}

Pass::Pass(const gpu::Context& ctx, const GpuScene* scene, SceneUse use, const char* shader, std::vector<PassResource> resources,
           std::vector<gpu::SpecConstant> spec, uint32_t push_bytes)
    : scene_(scene), use_(use), push_bytes_(push_bytes), resources_(std::move(resources)) {
  std::vector<gpu::Binding> bindings;
  const bool punctual = scene_ && (use_.lights || use_.shifts) && scene_->has_punctual();
  if (scene_) bindings = scene_->bindings(use_.lights, use_.history);
  for (const auto& r : resources_) bindings.push_back({r.binding, r.type});
  if (scene_ && use_.history && scene_->lod_mapping_compiled()) spec.push_back({SPEC_LOD_MAPPING, VK_TRUE});
  if (punctual) spec.push_back({SPEC_PUNCTUAL, VK_TRUE});
  if (scene_) scene_->add_spec(spec);
  pipeline_ = std::make_unique<gpu::ComputePipeline>(ctx, scene_ ? scene_->shader(shader) : std::string(shader), bindings, spec,
                                                      push_bytes_);
  for (auto& s : sets_) s = std::make_unique<gpu::DescriptorSet>(ctx, *pipeline_);
  rebind();
}

Pass::~Pass() = default;

void Pass::rebind() {
  for (int parity = 0; parity < 2; ++parity) {
    auto& set = *sets_[size_t(parity)];
    if (scene_) scene_->bind(set, use_.lights, use_.history, parity);
    for (const auto& r : resources_) set.bind_buffer(r.binding, r.buffer(parity));
  }
}

void Pass::dispatch_2d(VkCommandBuffer cmd, int parity, uint32_t width, uint32_t height, const void* push) const {
  gpu::dispatch_2d(cmd, *pipeline_, *sets_[size_t(parity & 1)], width, height, push, push ? push_bytes_ : 0);
}

void Pass::dispatch_layers(VkCommandBuffer cmd, int parity, uint32_t width, uint32_t height, uint32_t layers) const {
  gpu::dispatch_layers(cmd, *pipeline_, *sets_[size_t(parity & 1)], width, height, layers);
}

void Pass::dispatch_1d(VkCommandBuffer cmd, int parity, uint32_t count, const void* push) const {
  gpu::dispatch_1d(cmd, *pipeline_, *sets_[size_t(parity & 1)], count, push, push ? push_bytes_ : 0);
}

void Pass::dispatch_indirect(VkCommandBuffer cmd, int parity, const gpu::Buffer& args, VkDeviceSize offset, const void* push) const {
  gpu::dispatch_indirect(cmd, *pipeline_, *sets_[size_t(parity & 1)], args, offset, push, push ? push_bytes_ : 0);
}

}  // namespace strata::render
