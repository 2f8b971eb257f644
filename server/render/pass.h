#pragma once
// A compute pass declared where it is used: its shader and, once, every resource it reads or
// writes at which binding. The pipeline's layout and the descriptor sets are both made from that
// one declaration, so no binding list is written twice. A pass has one descriptor set per frame
// parity: resources that are ping-pong histories (PingPong) and the scene's two frame slots swap
// roles every frame, and the set of parity p binds them as frame p sees them.
#include <array>
#include <cstdint>
#include <functional>
#include <memory>
#include <string>
#include <vector>

#include "gpu/pipeline.h"
#include "render/scene_gpu.h"

namespace strata::render {

// A device-local storage buffer of `bytes` (the per-session buffers of the ReSTIR stages).
gpu::Buffer device_storage(const gpu::Context& ctx, size_t bytes, const std::string& name);

// Two buffers that swap roles every frame: current(p) is written by frame parity p, previous(p)
// holds what the frame before wrote (the history a temporal pass reads).
class PingPong {
 public:
  PingPong() = default;
  PingPong(const gpu::Context& ctx, size_t bytes, const std::string& name, VkBufferUsageFlags usage = gpu::k_storage_usage);
  const gpu::Buffer& current(int parity) const { return slots_[size_t(parity & 1)]; }
  const gpu::Buffer& previous(int parity) const { return slots_[size_t(1 - (parity & 1))]; }
  uint64_t size() const { return slots_[0].size() + slots_[1].size(); }

 private:
  std::array<gpu::Buffer, 2> slots_;
};

enum class Access { read, write, read_write };

// One resource of a pass: a binding, its descriptor type, how the pass uses it, and the buffer
// bound there for each frame parity.
struct PassResource {
  uint32_t binding;
  VkDescriptorType type;
  Access access;
  std::function<const gpu::Buffer&(int parity)> buffer;
};

// Declaration helpers: a uniform, a storage buffer, and either role of a ping-pong history.
PassResource uniform(uint32_t binding, const gpu::Buffer& buffer);
PassResource storage(uint32_t binding, Access access, const gpu::Buffer& buffer);
PassResource history_current(uint32_t binding, Access access, const PingPong& history);
PassResource history_previous(uint32_t binding, const PingPong& history);

// Which of the scene bridge's bindings a pass uses (shaders/include/scene_bridge.glsl).
struct SceneUse {
  bool lights = false;   // emitter tables (light sampling)
  bool history = false;  // the previous frame's TLAS and instance records
  // The pass shifts paths (restir/path_space.glsl) without sampling lights: a path that ends at a
  // punctual light is evaluated there as one (SPEC_PUNCTUAL; the records are read by address).
  bool shifts = false;
};

class Pass {
 public:
  // `scene` null: the pass binds no scene resources. `push_bytes`: the size of the shader's push
  // constant block, which every dispatch then passes (`push`).
  Pass(const gpu::Context& ctx, const GpuScene* scene, SceneUse use, const char* shader, std::vector<PassResource> resources,
       std::vector<gpu::SpecConstant> spec = {}, uint32_t push_bytes = 0);
  ~Pass();
  Pass(const Pass&) = delete;
  Pass& operator=(const Pass&) = delete;

  // Binds every resource again (after a buffer it declared was reallocated in place).
  void rebind();
  const std::string& shader() const { return pipeline_->name(); }
  const std::vector<PassResource>& resources() const { return resources_; }

  void dispatch_2d(VkCommandBuffer cmd, int parity, uint32_t width, uint32_t height, const void* push = nullptr) const;
  void dispatch_layers(VkCommandBuffer cmd, int parity, uint32_t width, uint32_t height, uint32_t layers) const;
  void dispatch_1d(VkCommandBuffer cmd, int parity, uint32_t count, const void* push = nullptr) const;
  // Workgroup counts read from `args` at `offset` (VkDispatchIndirectCommand), e.g. one thread per
  // entry of a dense domain list that an earlier pass compacted.
  void dispatch_indirect(VkCommandBuffer cmd, int parity, const gpu::Buffer& args, VkDeviceSize offset = 0,
                         const void* push = nullptr) const;

 private:
  const GpuScene* scene_;
  SceneUse use_;
  uint32_t push_bytes_ = 0;
  std::vector<PassResource> resources_;
  std::unique_ptr<gpu::ComputePipeline> pipeline_;
  std::array<std::unique_ptr<gpu::DescriptorSet>, 2> sets_;
};

}  // namespace strata::render
