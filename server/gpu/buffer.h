#pragma once
// Vulkan buffers with their own memory. Host-visible buffers stay mapped; device-local buffers are
// filled and read through a staging copy.
#include <cstdint>
#include <algorithm>
#include <cstring>
#include <span>
#include <string>
#include <vector>

#include <glm/glm.hpp>

#include "gpu/context.h"

namespace strata::gpu {

enum class Memory { Device, Host };

class Buffer {
 public:
  Buffer() = default;
  Buffer(const Context& ctx, VkDeviceSize size, VkBufferUsageFlags usage, Memory memory, std::string name);
  ~Buffer();
  Buffer(Buffer&& other) noexcept;
  Buffer& operator=(Buffer&& other) noexcept;
  Buffer(const Buffer&) = delete;
  Buffer& operator=(const Buffer&) = delete;

  VkBuffer handle() const { return buffer_; }
  VkDeviceSize size() const { return size_; }
  VkDeviceAddress address() const { return address_; }
  const std::string& name() const { return name_; }
  bool valid() const { return buffer_ != VK_NULL_HANDLE; }
  void* mapped() const { return mapped_; }

  // Copies bytes in at `offset`: directly when mapped, else through a staging buffer (waits).
  void upload(const void* data, VkDeviceSize bytes, VkDeviceSize offset = 0);
  template <class T>
  void upload(std::span<const T> items) { upload(items.data(), items.size_bytes()); }
  void download(void* out, VkDeviceSize bytes, VkDeviceSize offset = 0) const;
  template <class T>
  std::vector<T> download_as(size_t count) const {
    std::vector<T> v(count);
    download(v.data(), count * sizeof(T));
    return v;
  }

 private:
  void release();
  const Context* ctx_ = nullptr;
  VkBuffer buffer_ = VK_NULL_HANDLE;
  VkDeviceMemory memory_ = VK_NULL_HANDLE;
  VkDeviceSize size_ = 0;
  VkDeviceAddress address_ = 0;
  void* mapped_ = nullptr;
  std::string name_;
};

// A device address as the two 32-bit words a shader's uvec2 buffer reference takes (low, high).
inline glm::uvec2 address_words(VkDeviceAddress a) { return glm::uvec2(uint32_t(a), uint32_t(a >> 32)); }

// Usage for buffers that shaders read or write.
constexpr VkBufferUsageFlags k_storage_usage = VK_BUFFER_USAGE_STORAGE_BUFFER_BIT | VK_BUFFER_USAGE_TRANSFER_DST_BIT |
                                               VK_BUFFER_USAGE_TRANSFER_SRC_BIT | VK_BUFFER_USAGE_SHADER_DEVICE_ADDRESS_BIT;
// A storage buffer that also holds arguments of vkCmdDispatchIndirect.
constexpr VkBufferUsageFlags k_indirect_usage = k_storage_usage | VK_BUFFER_USAGE_INDIRECT_BUFFER_BIT;

// A buffer holding `items`, at least `min_bytes` long (zero-sized arrays still get a valid buffer).
template <class T>
Buffer make_buffer(const Context& ctx, std::span<const T> items, VkBufferUsageFlags usage, Memory memory,
                   std::string name) {
  VkDeviceSize bytes = std::max<VkDeviceSize>(items.size_bytes(), 16);
  Buffer b(ctx, bytes, usage, memory, std::move(name));
  if (!items.empty()) b.upload(items.data(), items.size_bytes());
  return b;
}

}  // namespace strata::gpu
