#include "gpu/timer.h"

#include <algorithm>

namespace strata::gpu {

PassTimer::PassTimer(const Context& ctx, uint32_t max_passes) : ctx_(ctx), capacity_(max_passes) {
  VkQueryPoolCreateInfo ci{VK_STRUCTURE_TYPE_QUERY_POOL_CREATE_INFO};
  ci.queryType = VK_QUERY_TYPE_TIMESTAMP;
  ci.queryCount = 2 * max_passes;
  check(vkCreateQueryPool(ctx.device(), &ci, nullptr, &pool_), "vkCreateQueryPool");
}

PassTimer::~PassTimer() { vkDestroyQueryPool(ctx_.device(), pool_, nullptr); }

void PassTimer::reset(VkCommandBuffer cmd) {
  vkCmdResetQueryPool(cmd, pool_, 0, 2 * capacity_);
  names_.clear();
}

void PassTimer::begin(VkCommandBuffer cmd, const std::string& pass) {
  if (names_.size() >= capacity_) throw GpuError("more than " + std::to_string(capacity_) + " timed passes in a frame");
  names_.push_back(pass);
  vkCmdWriteTimestamp2(cmd, VK_PIPELINE_STAGE_2_ALL_COMMANDS_BIT, pool_, uint32_t(2 * (names_.size() - 1)));
}

void PassTimer::end(VkCommandBuffer cmd) {
  vkCmdWriteTimestamp2(cmd, VK_PIPELINE_STAGE_2_ALL_COMMANDS_BIT, pool_, uint32_t(2 * (names_.size() - 1) + 1));
}

std::vector<PassTime> PassTimer::read() const {
  std::vector<PassTime> out;
  if (names_.empty()) return out;
  std::vector<uint64_t> ticks(2 * names_.size());
  check(vkGetQueryPoolResults(ctx_.device(), pool_, 0, uint32_t(ticks.size()), ticks.size() * sizeof(uint64_t),
                              ticks.data(), sizeof(uint64_t), VK_QUERY_RESULT_64_BIT | VK_QUERY_RESULT_WAIT_BIT),
        "vkGetQueryPoolResults");
  double ns_per_tick = ctx_.timestamp_period_ns();
  for (size_t i = 0; i < names_.size(); ++i) {
    double ms = double(ticks[2 * i + 1] - ticks[2 * i]) * ns_per_tick * 1e-6;
    auto it = std::find_if(out.begin(), out.end(), [&](const PassTime& p) { return p.pass == names_[i]; });
    if (it == out.end()) out.push_back({names_[i], ms});
    else it->ms += ms;
  }
  return out;
}

}  // namespace strata::gpu
