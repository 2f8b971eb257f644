#pragma once
// GPU time per pass from Vulkan timestamp queries.
#include <string>
#include <utility>
#include <vector>

#include "gpu/context.h"

namespace strata::gpu {

struct PassTime {
  std::string pass;
  double ms = 0.0;
};

class PassTimer {
 public:
  PassTimer(const Context& ctx, uint32_t max_passes);
  ~PassTimer();
  PassTimer(const PassTimer&) = delete;
  PassTimer& operator=(const PassTimer&) = delete;

  void reset(VkCommandBuffer cmd);                        // start of a frame's command buffer
  void begin(VkCommandBuffer cmd, const std::string& pass);
  void end(VkCommandBuffer cmd);
  // After the command buffer completed: the passes in order, durations summed per name.
  std::vector<PassTime> read() const;

 private:
  const Context& ctx_;
  VkQueryPool pool_ = VK_NULL_HANDLE;
  uint32_t capacity_ = 0;
  std::vector<std::string> names_;
};

}  // namespace strata::gpu
