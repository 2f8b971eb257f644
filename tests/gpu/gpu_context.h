#pragma once
// One Vulkan context for the whole GPU test binary, with the Khronos validation layer on.
// GpuTest fails any test during which the layer reported an error.
#include <gtest/gtest.h>

#include "gpu/context.h"

namespace strata::test {

gpu::Context& gpu_context();

class GpuTest : public ::testing::Test {
 protected:
  void SetUp() override { errors_before_ = gpu_context().validation_errors(); }
  void TearDown() override {
    auto& ctx = gpu_context();
    EXPECT_EQ(ctx.validation_errors(), errors_before_) << "Vulkan validation errors during this test; first messages:\n"
                                                       << [&] {
                                                            std::string all;
                                                            for (const auto& m : ctx.validation_messages()) all += m + "\n";
                                                            return all;
                                                          }();
  }
  uint64_t errors_before_ = 0;
};

}  // namespace strata::test
