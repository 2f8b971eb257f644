#pragma once
// The Vulkan device strata renders with: headless, compute queue, ray queries, acceleration
// structures, buffer device addresses, timestamps. One Context per process.
#include <atomic>
#include <cstdint>
#include <functional>
#include <future>
#include <map>
#include <memory>
#include <mutex>
#include <stdexcept>
#include <string>
#include <vector>

#include <vulkan/vulkan.h>

namespace strata::gpu {

struct GpuError : std::runtime_error {
  using std::runtime_error::runtime_error;
};

// Throws GpuError naming the call and the VkResult.
void check(VkResult result, const char* what);

struct ContextOptions {
  // Substring of the device name to use (case-insensitive), e.g. "llvmpipe" or "NVIDIA".
  // Empty: the STRATA_DEVICE environment variable, else lavapipe if present, else the first
  // device that supports everything strata needs.
  std::string device;
  // Khronos validation layer; also enabled by STRATA_VALIDATION=1, and in debug builds whenever
  // the layer is installed.
  bool validation = false;
};

// Extension function pointers that the loader does not export statically.
struct RayTracingFns {
  PFN_vkGetAccelerationStructureBuildSizesKHR get_build_sizes = nullptr;
  PFN_vkCreateAccelerationStructureKHR create_as = nullptr;
  PFN_vkDestroyAccelerationStructureKHR destroy_as = nullptr;
  PFN_vkCmdBuildAccelerationStructuresKHR cmd_build_as = nullptr;
  PFN_vkGetAccelerationStructureDeviceAddressKHR get_as_address = nullptr;
};

class Context {
 public:
  explicit Context(const ContextOptions& options = {});
  ~Context();
  Context(const Context&) = delete;
  Context& operator=(const Context&) = delete;

  VkInstance instance() const { return instance_; }
  VkPhysicalDevice physical_device() const { return physical_; }
  VkDevice device() const { return device_; }
  VkQueue queue() const { return queue_; }
  uint32_t queue_family() const { return queue_family_; }
  const std::string& device_name() const { return device_name_; }
  const VkPhysicalDeviceProperties& properties() const { return properties_; }
  const RayTracingFns& rt() const { return rt_; }
  float timestamp_period_ns() const { return properties_.limits.timestampPeriod; }
  bool validation_enabled() const { return validation_; }

  // Validation messages of severity error seen so far (tests assert this stays 0).
  uint64_t validation_errors() const { return validation_errors_.load(); }
  std::vector<std::string> validation_messages() const;

  uint32_t find_memory_type(uint32_t type_bits, VkMemoryPropertyFlags flags) const;

  // Records with `record` into a fresh command buffer, submits, and waits.
  void submit_and_wait(const std::function<void(VkCommandBuffer)>& record) const;

  // Compiled pipelines shared by every user of this context for its lifetime (gpu/pipeline.cpp):
  // a pipeline is compiled once per process, which matters where compiling is slow (lavapipe
  // compiles a ray-query shader with LLVM for seconds). Keyed by shader, layout and constants.
  // Threads may create different pipelines at once (gpu::create_pipelines); a second caller of a
  // key being made waits for that one.
  std::shared_ptr<void> cached_pipeline(const std::string& key, const std::function<std::shared_ptr<void>()>& make) const;

 private:
  mutable std::mutex pipelines_mutex_;
  mutable std::map<std::string, std::shared_future<std::shared_ptr<void>>> pipelines_;
  static VkBool32 VKAPI_PTR debug_callback(VkDebugUtilsMessageSeverityFlagBitsEXT severity,
                                           VkDebugUtilsMessageTypeFlagsEXT types,
                                           const VkDebugUtilsMessengerCallbackDataEXT* data, void* user);
  void create_instance(bool validation);
  void pick_physical_device(const std::string& wanted);
  void create_device();

  VkInstance instance_ = VK_NULL_HANDLE;
  VkDebugUtilsMessengerEXT messenger_ = VK_NULL_HANDLE;
  VkPhysicalDevice physical_ = VK_NULL_HANDLE;
  VkDevice device_ = VK_NULL_HANDLE;
  VkQueue queue_ = VK_NULL_HANDLE;
  VkCommandPool command_pool_ = VK_NULL_HANDLE;
  uint32_t queue_family_ = 0;
  std::string device_name_;
  VkPhysicalDeviceProperties properties_{};
  VkPhysicalDeviceMemoryProperties memory_{};
  RayTracingFns rt_;
  bool validation_ = false;
  std::atomic<uint64_t> validation_errors_{0};
  mutable std::mutex messages_mutex_;
  std::vector<std::string> messages_;
  // vkQueueSubmit and the command pool need external sync; recursive so that a recording callback may
  // itself upload through a staging copy.
  mutable std::recursive_mutex queue_mutex_;
};

}  // namespace strata::gpu
