// The pass machinery of the staged pipeline (render/pass.h, gpu/timer.h): a pass declared once
// binds its ping-pong resources by frame parity; an indirect dispatch covers what the direct one
// does; the pass timer holds as many passes as it was sized for (a 12-pass method works) and
// refuses one more; the renderer sizes it from the method's stages.
#include <glm/gtc/matrix_transform.hpp>

#include "gpu/gpu_context.h"
#include "include/bindings.h"
#include "include/frame_data.h"
#include "render/frame_constants.h"
#include "render/pass.h"
#include "render/renderer.h"
#include "restir/primary_data.h"
#include "scene/scene_io.h"
#include "support/test_scenes.h"

namespace strata::test {
namespace {

class Passes : public GpuTest {};

TEST_F(Passes, PingPongResourcesSwapWithTheFrameParity) {
  render::PingPong history(gpu_context(), 64, "test history");
  render::PassResource cur = render::history_current(BINDING_RESERVOIRS_OUT, render::Access::write, history);
  render::PassResource prev = render::history_previous(BINDING_RESERVOIRS_IN, history);
  EXPECT_EQ(cur.buffer(0).handle(), prev.buffer(1).handle());
  EXPECT_EQ(cur.buffer(1).handle(), prev.buffer(0).handle());
  EXPECT_NE(cur.buffer(0).handle(), cur.buffer(1).handle());
  EXPECT_EQ(history.size(), 128u);
}

TEST_F(Passes, TimerHoldsTwelvePassesAndRefusesAThirteenth) {
  gpu::PassTimer timer(gpu_context(), 12);
  gpu::Buffer scratch(gpu_context(), 1024, gpu::k_storage_usage, gpu::Memory::Device, "scratch");
  gpu_context().submit_and_wait([&](VkCommandBuffer cmd) {
    timer.reset(cmd);
    for (int i = 0; i < 12; ++i) {
      timer.begin(cmd, "pass" + std::to_string(i));
      vkCmdFillBuffer(cmd, scratch.handle(), 0, VK_WHOLE_SIZE, uint32_t(i));
      gpu::compute_barrier(cmd);
      timer.end(cmd);
    }
    EXPECT_THROW(timer.begin(cmd, "one too many"), gpu::GpuError);
  });
  auto times = timer.read();
  ASSERT_EQ(times.size(), 12u);
  for (int i = 0; i < 12; ++i) {
    EXPECT_EQ(times[size_t(i)].pass, "pass" + std::to_string(i));
    EXPECT_GE(times[size_t(i)].ms, 0.0);
  }
}

// restir-splat with spatial reuse records update, primary, initial, four splat passes, spatial and
// shade: nine, one more than the fixed eight the timer used to have.
TEST_F(Passes, RendererSizesTheTimerFromTheStages) {
  scene::Scene s = scene::builtin_scene("cornell");
  render::RenderSettings rs;
  rs.width = 8;
  rs.height = 8;
  rs.method = "restir-splat";
  rs.max_depth = 2;
  render::Renderer r(gpu_context(), s, rs);
  r.render(s.frame_state(0), 0);
  auto f = r.render(s.frame_state(1), 1);
  EXPECT_EQ(f.stats.pass_ms.size(), 9u);
  EXPECT_EQ(f.stats.pass_ms.front().pass, "update");
  EXPECT_EQ(f.stats.pass_ms.back().pass, "shade");
}

// The primary pass dispatched indirectly, with the workgroup counts in a buffer, writes exactly
// what the direct dispatch writes.
TEST_F(Passes, IndirectDispatchCoversTheSameWorkAsTheDirectOne) {
  auto& ctx = gpu_context();
  scene::Scene s = scene::builtin_scene("cornell");
  render::GpuScene scene(ctx, s);
  constexpr uint32_t w = 20, h = 12;
  gpu::Buffer constants(ctx, sizeof(gpu::GpuFrameConstants), VK_BUFFER_USAGE_UNIFORM_BUFFER_BIT, gpu::Memory::Host, "constants");
  gpu::Buffer direct(ctx, sizeof(gpu::GpuPrimaryHit) * w * h, gpu::k_storage_usage, gpu::Memory::Device, "direct");
  gpu::Buffer indirect(ctx, sizeof(gpu::GpuPrimaryHit) * w * h, gpu::k_storage_usage, gpu::Memory::Device, "indirect");
  const uint32_t groups[3] = {(w + 7) / 8, (h + 7) / 8, 1};
  gpu::Buffer args(ctx, sizeof groups, gpu::k_indirect_usage, gpu::Memory::Host, "dispatch arguments");
  args.upload(groups, sizeof groups);
  render::Pass a(ctx, &scene, {}, "primary",
                 {render::uniform(BINDING_FRAME, constants), render::storage(BINDING_PRIMARY, render::Access::write, direct)});
  render::Pass b(ctx, &scene, {}, "primary",
                 {render::uniform(BINDING_FRAME, constants), render::storage(BINDING_PRIMARY, render::Access::write, indirect)});
  ctx.submit_and_wait([&](VkCommandBuffer cmd) {
    scene::FrameState f = s.frame_state(0);
    scene.record_update(cmd, f);
    render::FrameSetup setup;
    setup.width = w;
    setup.height = h;
    gpu::GpuFrameConstants c = render::make_frame_constants(f, s.environment, scene, setup);
    constants.upload(&c, sizeof c);
    vkCmdFillBuffer(cmd, indirect.handle(), 0, VK_WHOLE_SIZE, 0xFFFFFFFFu);
    gpu::compute_barrier(cmd);
    a.dispatch_2d(cmd, 0, w, h);
    b.dispatch_indirect(cmd, 0, args);
  });
  auto x = direct.download_as<gpu::GpuPrimaryHit>(w * h);
  auto y = indirect.download_as<gpu::GpuPrimaryHit>(w * h);
  uint32_t hits = 0;
  for (size_t i = 0; i < x.size(); ++i) {
    EXPECT_EQ(std::memcmp(&x[i], &y[i], sizeof x[i]), 0) << "pixel " << i;
    hits += (x[i].flags & gpu::PRIMARY_HIT) != 0u;
  }
  EXPECT_GT(hits, w * h / 2) << "most pixel-centre rays hit the box: the comparison must cover hits";
}

}  // namespace
}  // namespace strata::test
