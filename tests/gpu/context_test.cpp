// Device selection: a clear error naming what is wrong, and the default device is capable.
#include "gpu/gpu_context.h"

namespace strata::test {
namespace {

TEST(GpuContext, UnknownDeviceNameIsAClearError) {
  try {
    gpu::Context ctx({"no-such-device-xyz", false});
    FAIL() << "expected an error";
  } catch (const gpu::GpuError& e) {
    std::string msg = e.what();
    EXPECT_NE(msg.find("no-such-device-xyz"), std::string::npos) << msg;
    EXPECT_NE(msg.find("devices:"), std::string::npos) << msg;  // lists what exists
  }
}

TEST(GpuContext, DefaultDeviceHasRayQueriesAndTimestamps) {
  auto& ctx = gpu_context();
  EXPECT_FALSE(ctx.device_name().empty());
  EXPECT_GT(ctx.timestamp_period_ns(), 0.0f);
  EXPECT_TRUE(ctx.validation_enabled());
}

}  // namespace
}  // namespace strata::test
