#include "gpu/context.h"

#include <algorithm>
#include <cctype>
#include <cstdlib>
#include <cstring>
#include <iostream>
#include <sstream>

namespace strata::gpu {
namespace {

constexpr const char* k_validation_layer = "VK_LAYER_KHRONOS_validation";
constexpr const char* k_device_extensions[] = {
    VK_KHR_ACCELERATION_STRUCTURE_EXTENSION_NAME,
    VK_KHR_RAY_QUERY_EXTENSION_NAME,
    VK_KHR_DEFERRED_HOST_OPERATIONS_EXTENSION_NAME,
};

std::string lower(std::string s) {
  std::transform(s.begin(), s.end(), s.begin(), [](unsigned char c) { return char(std::tolower(c)); });
  return s;
}

bool env_flag(const char* name) {
  const char* v = std::getenv(name);
  return v && *v && std::strcmp(v, "0") != 0;
}

bool has_layer(const char* name) {
  uint32_t count = 0;
  vkEnumerateInstanceLayerProperties(&count, nullptr);
  std::vector<VkLayerProperties> layers(count);
  vkEnumerateInstanceLayerProperties(&count, layers.data());
  return std::any_of(layers.begin(), layers.end(), [&](const auto& l) { return std::strcmp(l.layerName, name) == 0; });
}

// Everything strata needs from a device; returns the first missing feature, or "".
std::string missing_feature(VkPhysicalDevice pd) {
  VkPhysicalDeviceProperties props;
  vkGetPhysicalDeviceProperties(pd, &props);
  if (props.apiVersion < VK_API_VERSION_1_3) return "Vulkan 1.3";
  uint32_t count = 0;
  vkEnumerateDeviceExtensionProperties(pd, nullptr, &count, nullptr);
  std::vector<VkExtensionProperties> exts(count);
  vkEnumerateDeviceExtensionProperties(pd, nullptr, &count, exts.data());
  for (const char* want : k_device_extensions) {
    bool found = std::any_of(exts.begin(), exts.end(), [&](const auto& e) { return std::strcmp(e.extensionName, want) == 0; });
    if (!found) return want;
  }
  VkPhysicalDeviceRayQueryFeaturesKHR rq{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_RAY_QUERY_FEATURES_KHR};
  VkPhysicalDeviceAccelerationStructureFeaturesKHR as{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_ACCELERATION_STRUCTURE_FEATURES_KHR, &rq};
  VkPhysicalDeviceVulkan13Features v13{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_VULKAN_1_3_FEATURES, &as};
  VkPhysicalDeviceVulkan12Features v12{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_VULKAN_1_2_FEATURES, &v13};
  VkPhysicalDeviceFeatures2 f2{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_FEATURES_2, &v12};
  vkGetPhysicalDeviceFeatures2(pd, &f2);
  if (!v13.synchronization2) return "synchronization2 (Vulkan 1.3)";
  if (!v13.maintenance4) return "maintenance4 (Vulkan 1.3)";
  if (!rq.rayQuery) return "rayQuery (VK_KHR_ray_query)";
  if (!as.accelerationStructure) return "accelerationStructure (VK_KHR_acceleration_structure)";
  if (!v12.bufferDeviceAddress) return "bufferDeviceAddress (Vulkan 1.2)";
  if (!props.limits.timestampComputeAndGraphics) return "timestampComputeAndGraphics";
  return "";
}

}  // namespace

void check(VkResult result, const char* what) {
  if (result != VK_SUCCESS) {
    std::ostringstream os;
    os << what << " failed with VkResult " << int(result);
    throw GpuError(os.str());
  }
}

Context::Context(const ContextOptions& options) {
  bool validation = options.validation || env_flag("STRATA_VALIDATION");
#ifndef NDEBUG
  // Debug builds validate whenever the layer is installed (STRATA_VALIDATION=0 opts out).
  const char* opt = std::getenv("STRATA_VALIDATION");
  if (!(opt && std::strcmp(opt, "0") == 0) && has_layer(k_validation_layer)) validation = true;
#endif
  create_instance(validation);
  std::string wanted = options.device;
  if (wanted.empty()) {
    if (const char* env = std::getenv("STRATA_DEVICE")) wanted = env;
  }
  pick_physical_device(wanted);
  create_device();
}

std::shared_ptr<void> Context::cached_pipeline(const std::string& key, const std::function<std::shared_ptr<void>()>& make) const {
  // The table's lock is not held while a pipeline is made: other keys are made alongside it.
  std::promise<std::shared_ptr<void>> made;
  std::shared_future<std::shared_ptr<void>> slot;
  bool maker = false;
  {
    std::lock_guard lock(pipelines_mutex_);
    auto [it, first] = pipelines_.try_emplace(key);
    if (first) it->second = made.get_future().share();
    slot = it->second;
    maker = first;
  }
  if (maker) {
    try {
      made.set_value(make());
    } catch (...) {
      made.set_exception(std::current_exception());  // this caller's and the waiters' error
      std::lock_guard lock(pipelines_mutex_);
      pipelines_.erase(key);  // a later caller tries again
    }
  }
  return slot.get();
}

Context::~Context() {
  if (device_) {
    vkDeviceWaitIdle(device_);
    pipelines_.clear();  // they need the device
    vkDestroyCommandPool(device_, command_pool_, nullptr);
    vkDestroyDevice(device_, nullptr);
  }
  if (messenger_) {
    auto destroy = reinterpret_cast<PFN_vkDestroyDebugUtilsMessengerEXT>(
        vkGetInstanceProcAddr(instance_, "vkDestroyDebugUtilsMessengerEXT"));
    if (destroy) destroy(instance_, messenger_, nullptr);
  }
  if (instance_) vkDestroyInstance(instance_, nullptr);
}

VkBool32 VKAPI_PTR Context::debug_callback(VkDebugUtilsMessageSeverityFlagBitsEXT severity,
                                           VkDebugUtilsMessageTypeFlagsEXT, const VkDebugUtilsMessengerCallbackDataEXT* data,
                                           void* user) {
  auto* self = static_cast<Context*>(user);
  if (severity >= VK_DEBUG_UTILS_MESSAGE_SEVERITY_ERROR_BIT_EXT) {
    self->validation_errors_++;
    std::lock_guard lock(self->messages_mutex_);
    if (self->messages_.size() < 64) self->messages_.emplace_back(data->pMessage ? data->pMessage : "");
    std::cerr << "[vulkan validation] " << (data->pMessage ? data->pMessage : "") << "\n";
  }
  return VK_FALSE;
}

std::vector<std::string> Context::validation_messages() const {
  std::lock_guard lock(messages_mutex_);
  return messages_;
}

void Context::create_instance(bool validation) {
  if (validation && !has_layer(k_validation_layer)) {
    throw GpuError("validation was requested but VK_LAYER_KHRONOS_validation is not installed "
                   "(Debian package vulkan-validationlayers)");
  }
  validation_ = validation;
  VkApplicationInfo app{VK_STRUCTURE_TYPE_APPLICATION_INFO};
  app.pApplicationName = "strata";
  app.applicationVersion = VK_MAKE_VERSION(0, 1, 0);
  app.pEngineName = "strata";
  app.apiVersion = VK_API_VERSION_1_3;

  std::vector<const char*> layers;
  std::vector<const char*> extensions;
  VkDebugUtilsMessengerCreateInfoEXT dbg{VK_STRUCTURE_TYPE_DEBUG_UTILS_MESSENGER_CREATE_INFO_EXT};
  dbg.messageSeverity = VK_DEBUG_UTILS_MESSAGE_SEVERITY_WARNING_BIT_EXT | VK_DEBUG_UTILS_MESSAGE_SEVERITY_ERROR_BIT_EXT;
  dbg.messageType = VK_DEBUG_UTILS_MESSAGE_TYPE_GENERAL_BIT_EXT | VK_DEBUG_UTILS_MESSAGE_TYPE_VALIDATION_BIT_EXT |
                    VK_DEBUG_UTILS_MESSAGE_TYPE_PERFORMANCE_BIT_EXT;
  dbg.pfnUserCallback = &Context::debug_callback;
  dbg.pUserData = this;
  if (validation) {
    layers.push_back(k_validation_layer);
    extensions.push_back(VK_EXT_DEBUG_UTILS_EXTENSION_NAME);
  }
  VkInstanceCreateInfo ci{VK_STRUCTURE_TYPE_INSTANCE_CREATE_INFO};
  ci.pApplicationInfo = &app;
  ci.enabledLayerCount = uint32_t(layers.size());
  ci.ppEnabledLayerNames = layers.data();
  ci.enabledExtensionCount = uint32_t(extensions.size());
  ci.ppEnabledExtensionNames = extensions.data();
  if (validation) ci.pNext = &dbg;
  check(vkCreateInstance(&ci, nullptr, &instance_), "vkCreateInstance");
  if (validation) {
    auto create = reinterpret_cast<PFN_vkCreateDebugUtilsMessengerEXT>(
        vkGetInstanceProcAddr(instance_, "vkCreateDebugUtilsMessengerEXT"));
    if (!create) throw GpuError("vkCreateDebugUtilsMessengerEXT is unavailable");
    check(create(instance_, &dbg, nullptr, &messenger_), "vkCreateDebugUtilsMessengerEXT");
  }
}

void Context::pick_physical_device(const std::string& wanted) {
  uint32_t count = 0;
  vkEnumeratePhysicalDevices(instance_, &count, nullptr);
  std::vector<VkPhysicalDevice> devices(count);
  vkEnumeratePhysicalDevices(instance_, &count, devices.data());
  if (devices.empty()) {
    throw GpuError("no Vulkan device found; install mesa-vulkan-drivers (lavapipe) with deploy/install-deps.sh");
  }
  std::ostringstream seen;
  auto name_of = [](VkPhysicalDevice pd) {
    VkPhysicalDeviceProperties p;
    vkGetPhysicalDeviceProperties(pd, &p);
    return std::string(p.deviceName);
  };
  auto try_pick = [&](VkPhysicalDevice pd) {
    std::string why = missing_feature(pd);
    if (!why.empty()) {
      seen << "\n  " << name_of(pd) << ": lacks " << why;
      return false;
    }
    physical_ = pd;
    return true;
  };
  if (!wanted.empty()) {
    for (auto pd : devices) {
      if (lower(name_of(pd)).find(lower(wanted)) == std::string::npos) continue;
      if (try_pick(pd)) break;
    }
    if (!physical_) {
      std::ostringstream os;
      os << "no usable Vulkan device matches '" << wanted << "'; devices:";
      for (auto pd : devices) os << "\n  " << name_of(pd) << (missing_feature(pd).empty() ? "" : " (lacks " + missing_feature(pd) + ")");
      throw GpuError(os.str());
    }
  } else {
    // Default: lavapipe (deterministic, everywhere), else the first capable device.
    for (auto pd : devices)
      if (lower(name_of(pd)).find("llvmpipe") != std::string::npos && try_pick(pd)) break;
    for (auto pd : devices) {
      if (physical_) break;
      try_pick(pd);
    }
    if (!physical_) throw GpuError("no Vulkan device supports what strata needs:" + seen.str());
  }
  vkGetPhysicalDeviceProperties(physical_, &properties_);
  vkGetPhysicalDeviceMemoryProperties(physical_, &memory_);
  device_name_ = properties_.deviceName;
}

void Context::create_device() {
  uint32_t count = 0;
  vkGetPhysicalDeviceQueueFamilyProperties(physical_, &count, nullptr);
  std::vector<VkQueueFamilyProperties> families(count);
  vkGetPhysicalDeviceQueueFamilyProperties(physical_, &count, families.data());
  bool found = false;
  for (uint32_t i = 0; i < count; ++i) {
    if ((families[i].queueFlags & VK_QUEUE_COMPUTE_BIT) && families[i].timestampValidBits > 0) {
      queue_family_ = i;
      found = true;
      break;
    }
  }
  if (!found) throw GpuError(device_name_ + ": no compute queue with timestamps");

  float priority = 1.0f;
  VkDeviceQueueCreateInfo qci{VK_STRUCTURE_TYPE_DEVICE_QUEUE_CREATE_INFO};
  qci.queueFamilyIndex = queue_family_;
  qci.queueCount = 1;
  qci.pQueuePriorities = &priority;

  VkPhysicalDeviceRayQueryFeaturesKHR rq{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_RAY_QUERY_FEATURES_KHR};
  rq.rayQuery = VK_TRUE;
  VkPhysicalDeviceAccelerationStructureFeaturesKHR as{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_ACCELERATION_STRUCTURE_FEATURES_KHR, &rq};
  as.accelerationStructure = VK_TRUE;
  VkPhysicalDeviceVulkan13Features v13{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_VULKAN_1_3_FEATURES, &as};
  v13.synchronization2 = VK_TRUE;
  v13.maintenance4 = VK_TRUE;  // glslang targets SPIR-V 1.6 for Vulkan 1.3, which uses LocalSizeId
  VkPhysicalDeviceVulkan12Features v12{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_VULKAN_1_2_FEATURES, &v13};
  v12.bufferDeviceAddress = VK_TRUE;
  v12.scalarBlockLayout = VK_TRUE;
  VkPhysicalDeviceFeatures2 f2{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_FEATURES_2, &v12};

  VkDeviceCreateInfo ci{VK_STRUCTURE_TYPE_DEVICE_CREATE_INFO, &f2};
  ci.queueCreateInfoCount = 1;
  ci.pQueueCreateInfos = &qci;
  ci.enabledExtensionCount = uint32_t(std::size(k_device_extensions));
  ci.ppEnabledExtensionNames = k_device_extensions;
  check(vkCreateDevice(physical_, &ci, nullptr, &device_), "vkCreateDevice");
  vkGetDeviceQueue(device_, queue_family_, 0, &queue_);

  VkCommandPoolCreateInfo pci{VK_STRUCTURE_TYPE_COMMAND_POOL_CREATE_INFO};
  pci.flags = VK_COMMAND_POOL_CREATE_RESET_COMMAND_BUFFER_BIT | VK_COMMAND_POOL_CREATE_TRANSIENT_BIT;
  pci.queueFamilyIndex = queue_family_;
  check(vkCreateCommandPool(device_, &pci, nullptr, &command_pool_), "vkCreateCommandPool");

  auto load = [&](const char* name) {
    auto fn = vkGetDeviceProcAddr(device_, name);
    if (!fn) throw GpuError(std::string("device function missing: ") + name);
    return fn;
  };
  rt_.get_build_sizes = reinterpret_cast<PFN_vkGetAccelerationStructureBuildSizesKHR>(load("vkGetAccelerationStructureBuildSizesKHR"));
  rt_.create_as = reinterpret_cast<PFN_vkCreateAccelerationStructureKHR>(load("vkCreateAccelerationStructureKHR"));
  rt_.destroy_as = reinterpret_cast<PFN_vkDestroyAccelerationStructureKHR>(load("vkDestroyAccelerationStructureKHR"));
  rt_.cmd_build_as = reinterpret_cast<PFN_vkCmdBuildAccelerationStructuresKHR>(load("vkCmdBuildAccelerationStructuresKHR"));
  rt_.get_as_address = reinterpret_cast<PFN_vkGetAccelerationStructureDeviceAddressKHR>(load("vkGetAccelerationStructureDeviceAddressKHR"));
}

uint32_t Context::find_memory_type(uint32_t type_bits, VkMemoryPropertyFlags flags) const {
  for (uint32_t i = 0; i < memory_.memoryTypeCount; ++i) {
    if ((type_bits & (1u << i)) && (memory_.memoryTypes[i].propertyFlags & flags) == flags) return i;
  }
  throw GpuError("no Vulkan memory type with the requested properties");
}

void Context::submit_and_wait(const std::function<void(VkCommandBuffer)>& record) const {
  std::lock_guard lock(queue_mutex_);
  VkCommandBufferAllocateInfo ai{VK_STRUCTURE_TYPE_COMMAND_BUFFER_ALLOCATE_INFO};
  ai.commandPool = command_pool_;
  ai.level = VK_COMMAND_BUFFER_LEVEL_PRIMARY;
  ai.commandBufferCount = 1;
  VkCommandBuffer cmd;
  check(vkAllocateCommandBuffers(device_, &ai, &cmd), "vkAllocateCommandBuffers");
  VkCommandBufferBeginInfo bi{VK_STRUCTURE_TYPE_COMMAND_BUFFER_BEGIN_INFO};
  bi.flags = VK_COMMAND_BUFFER_USAGE_ONE_TIME_SUBMIT_BIT;
  VkFence fence = VK_NULL_HANDLE;
  try {
    check(vkBeginCommandBuffer(cmd, &bi), "vkBeginCommandBuffer");
    record(cmd);
    check(vkEndCommandBuffer(cmd), "vkEndCommandBuffer");
    VkFenceCreateInfo fci{VK_STRUCTURE_TYPE_FENCE_CREATE_INFO};
    check(vkCreateFence(device_, &fci, nullptr, &fence), "vkCreateFence");
    VkSubmitInfo si{VK_STRUCTURE_TYPE_SUBMIT_INFO};
    si.commandBufferCount = 1;
    si.pCommandBuffers = &cmd;
    check(vkQueueSubmit(queue_, 1, &si, fence), "vkQueueSubmit");
    check(vkWaitForFences(device_, 1, &fence, VK_TRUE, UINT64_MAX), "vkWaitForFences");
  } catch (...) {
    if (fence) vkDestroyFence(device_, fence, nullptr);
    vkFreeCommandBuffers(device_, command_pool_, 1, &cmd);
    throw;
  }
  vkDestroyFence(device_, fence, nullptr);
  vkFreeCommandBuffers(device_, command_pool_, 1, &cmd);
}

}  // namespace strata::gpu
