#include "gpu/gpu_context.h"

#include <memory>

namespace strata::test {

gpu::Context& gpu_context() {
  static std::unique_ptr<gpu::Context> ctx = [] {
    gpu::ContextOptions options;
    options.validation = true;
    return std::make_unique<gpu::Context>(options);
  }();
  return *ctx;
}

}  // namespace strata::test
