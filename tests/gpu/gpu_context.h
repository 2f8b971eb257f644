#pragma once
// One Vulkan context for the whole GPU test binary, with the Khronos validation layer on.
// GpuTest fails any test during which the layer reported an error.
#include <gtest/gtest.h>

#include <string>

#include "gpu/context.h"

namespace strata::test {

gpu::Context& gpu_context();

// gtest parameter names cannot contain '-': "lod-cliff" -> "lod_cliff".
inline std::string scene_param_name(const ::testing::TestParamInfo<std::string>& param) {
  std::string n = param.param;
  for (auto& ch : n)
    if (ch == '-') ch = '_';
  return n;
}

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
