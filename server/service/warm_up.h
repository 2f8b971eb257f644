#pragma once
// `stratad serve --warm-up METHODS`: the pipelines of the methods named are compiled at start, in parallel
// (gpu/pipeline_warmup.h), so that a session's first frame does not wait for lavapipe to compile
// them one after another. Which pipelines: those a renderer of each method creates for the
// built-in carousel at the default options. Progress shows on /readyz (503 while warming) and as
// log lines.
#include <atomic>
#include <string>
#include <thread>
#include <vector>

#include "gpu/context.h"
#include "service/config.h"

namespace strata::service {

class WarmUp {
 public:
  // Starts at once on a thread of its own; `methods` in the order to warm them (unknown names are
  // an std::invalid_argument naming --warm-up); `threads` devices compile in parallel.
  WarmUp(gpu::ContextOptions device, const ServiceConfig& config, std::vector<std::string> methods, unsigned threads);
  ~WarmUp();  // stops after the pipelines being compiled
  WarmUp(const WarmUp&) = delete;
  WarmUp& operator=(const WarmUp&) = delete;

 private:
  void run(const ServiceConfig& config);
  const gpu::ContextOptions device_;
  const std::vector<std::string> methods_;
  const unsigned threads_;
  std::atomic<bool> stop_{false};
  std::thread thread_;
};

// "restir-gather,pt" or "all" (every available method) or "none": the methods to warm.
std::vector<std::string> parse_warm_up(const std::string& list);

}  // namespace strata::service
