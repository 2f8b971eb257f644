// stratad serve --warm-up on a cold machine (Mesa's shader cache pointed at an empty folder): the
// restir-gather pipelines are compiled at start (/readyz answers 503 "warming pipelines" meanwhile
// and 200 after, a log line counts them, Mesa's cache fills), and a session's first frame then
// finds them compiled: it renders in a fraction of the compile time. GALLIVM_PERF=nopt (llvmpipe
// without LLVM's optimisation passes) keeps the compile, and so the test, about twice as short.
//
// The progressive start on a cold machine: a session's first frames are rendered by pt while its
// method's pipelines compile in the background, each frame saying so; the frame after the first
// stage of the compile is the method's, with a history reset that says why and its temporal pass
// held, and the frame after the second stage (the history passes) reuses history.
#include <csignal>

#include <gtest/gtest.h>

#include <algorithm>
#include <cstdlib>
#include <optional>

#include "harness.h"
#include "ops_util.h"

namespace strata::test {
namespace {

size_t files_under(const std::filesystem::path& dir) {
  size_t n = 0;
  for (const auto& e : std::filesystem::recursive_directory_iterator(dir))
    if (e.is_regular_file()) ++n;
  return n;
}

TEST(WarmUpTest, ColdCachePipelinesCompileAtStartNotInTheFirstFrame) {
  TempDir cache;
  ::setenv("MESA_SHADER_CACHE_DIR", cache.path.c_str(), 1);
  ::setenv("GALLIVM_PERF", "nopt", 1);
  const auto start = std::chrono::steady_clock::now();
  OpsDaemon daemon({"--http", "127.0.0.1:0", "--warm-up", "restir-gather"});
  ::unsetenv("MESA_SHADER_CACHE_DIR");
  ::unsetenv("GALLIVM_PERF");
  bool saw_warming = false;
  ASSERT_TRUE(wait_until([&] {
    const auto r = http_get(daemon.http_address(), "/readyz");
    if (r.status == 503 && r.body.find("warming pipelines") != std::string::npos) saw_warming = true;
    return r.status == 200;
  }, 600s)) << daemon.process().output();
  const double warm_s = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  EXPECT_TRUE(saw_warming) << "/readyz never said it was warming";
  EXPECT_NE(daemon.process().output().find("stratad: pipelines of restir-gather warm: 7 in "), std::string::npos)
      << daemon.process().output();
  EXPECT_GT(files_under(cache.path), 0u) << "Mesa's cache stayed empty";

  auto stub = v1::RenderService::NewStub(loopback_channel(daemon.address()));
  auto req = session_request("carousel", 16, 16);
  req.set_method("restir-gather");
  const v1::Session s = create_ok(*stub, req);
  const auto frames = stream_frames(*stub, s.name(), 1);
  ASSERT_EQ(frames.size(), 1u);
  // Compiling these pipelines takes tens of seconds here; rendering 16x16 with them, well under one.
  EXPECT_LT(frames[0].timing().render_ms(), 0.1 * warm_s * 1000.0)
      << "the first frame took " << frames[0].timing().render_ms() << " ms after a " << warm_s << " s warm-up";
  std::printf("warm-up %.1f s; first restir-gather frame at 16x16 %.0f ms\n", warm_s, frames[0].timing().render_ms());
}

// SIGTERM while a compile is in progress: the daemon says that it waits for the compile (LLVM cannot
// be cut short, and the code is kept in Mesa's cache), and a second signal ends it at once.
TEST(WarmUpTest, ColdCacheASecondSignalEndsTheWaitForACompileInProgress) {
  TempDir cache;
  ::setenv("MESA_SHADER_CACHE_DIR", cache.path.c_str(), 1);
  ::setenv("GALLIVM_PERF", "nopt", 1);
  OpsDaemon daemon({"--http", "127.0.0.1:0", "--warm-up", "restir-gather"});
  ::unsetenv("MESA_SHADER_CACHE_DIR");
  ::unsetenv("GALLIVM_PERF");
  ASSERT_EQ(http_get(daemon.http_address(), "/readyz").status, 503) << "restir-gather compiled too soon for this test";
  daemon.process().signal(SIGTERM);
  const std::string waiting = "waiting for the pipeline compile in progress";
  ASSERT_TRUE(wait_until([&] { return daemon.process().output().find(waiting) != std::string::npos; }, 30s))
      << daemon.process().output();
  const auto t0 = std::chrono::steady_clock::now();
  daemon.process().signal(SIGTERM);
  const auto status = daemon.process().wait_exit(15s);
  ASSERT_TRUE(status.has_value()) << "still running 15 s after the second signal: " << daemon.process().output();
  EXPECT_EQ(*status, 0);
  EXPECT_NE(daemon.process().output().find("exiting without waiting for the compile"), std::string::npos)
      << daemon.process().output();
  std::printf("exited %.2f s after the second signal\n",
              std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count());
}

TEST(WarmUpTest, ColdCacheProgressiveStartRendersPtUntilTheMethodIsCompiled) {
  TempDir cache;
  ::setenv("MESA_SHADER_CACHE_DIR", cache.path.c_str(), 1);
  ::setenv("GALLIVM_PERF", "nopt", 1);
  OpsDaemon daemon({"--progressive-start"});
  ::unsetenv("MESA_SHADER_CACHE_DIR");
  ::unsetenv("GALLIVM_PERF");
  auto stub = v1::RenderService::NewStub(loopback_channel(daemon.address()));
  // restir-di: the progressive start is the same for every method, and its pipelines compile in a
  // fraction of restir-gather's time.
  auto req = session_request("carousel", 16, 16);
  req.set_method("restir-di");
  const v1::Session s = create_ok(*stub, req);

  auto compiling = [](const v1::Frame& f) {
    const auto& passes = f.statistics().passes();
    return !passes.empty() && passes[0].pass() == "restir-di" && !passes[0].ran();
  };
  StreamClient stream(*stub);
  auto next_frame = [&, i = uint32_t(0)]() mutable -> std::optional<v1::Frame> {
    if (!stream.send(frame_input(i + 1, i == 0 ? s.name() : "", i))) return std::nullopt;
    ++i;
    return stream.read();
  };
  const auto first = next_frame();
  ASSERT_TRUE(first) << daemon.process().output();
  ASSERT_TRUE(compiling(*first)) << "the first frame was not pt's: " << daemon.process().output();
  EXPECT_NE(first->statistics().passes(0).reason().find("restir-di compiling: rendered by pt"), std::string::npos)
      << first->statistics().passes(0).reason();
  EXPECT_FALSE(first->statistics().has_reuse()) << "pt keeps no reservoirs";
  EXPECT_NE(daemon.process().output().find("the pipelines of restir-di compile in the background; pt renders its frames"),
            std::string::npos)
      << daemon.process().output();

  auto temporal = [](const v1::Frame& f) -> std::optional<v1::PassDecision> {
    for (const auto& p : f.statistics().passes())
      if (p.pass() == "temporal") return p;
    return std::nullopt;
  };

  // The stand-in's frames are paced while the method compiles: the next one starts no sooner than
  // 3x the last one's render time after it (at most 2 s later).
  const auto paced = next_frame();
  ASSERT_TRUE(paced) << daemon.process().output();
  if (compiling(*paced)) {
    const double expected_wait = std::min(3.0 * first->timing().render_ms(), 2000.0);
    EXPECT_GE(paced->timing().render_ms(), 0.5 * expected_wait)
        << "the second stand-in frame came " << paced->timing().render_ms() << " ms after it was asked for, the first took "
        << first->timing().render_ms() << " ms";
  }

  // No frames meanwhile: the compile has both cores. First the pipelines of a frame without history.
  const auto t0 = std::chrono::steady_clock::now();
  ASSERT_TRUE(wait_until([&] { return daemon.process().output().find("pipelines of restir-di compiled in") != std::string::npos; }, 170s))
      << "restir-di's first stage was not compiled within 170 s: " << daemon.process().output();
  const double first_s = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  const auto taken_over = next_frame();
  ASSERT_TRUE(taken_over) << daemon.process().output();
  EXPECT_FALSE(compiling(*taken_over));
  EXPECT_TRUE(taken_over->statistics().has_reuse()) << "the frame after the first stage is restir-di's";
  EXPECT_TRUE(taken_over->history_reset());
  EXPECT_NE(taken_over->history_reset_reason().find("restir-di's pipelines are compiled"), std::string::npos)
      << taken_over->history_reset_reason();
  // The method renders before its history passes are compiled (here about 30 s later): a renderer
  // whose temporal pipeline waited for its compile at creation would not.
  const bool second_stage_done = daemon.process().output().find("the pipelines of restir-di compiled: ") != std::string::npos;
  EXPECT_FALSE(second_stage_done) << "restir-di's first frame came only after its history passes were compiled";
  if (!second_stage_done) {
    EXPECT_NE(taken_over->history_reset_reason().find("its history passes held"), std::string::npos) << taken_over->history_reset_reason();
    const auto t = temporal(*taken_over);
    ASSERT_TRUE(t.has_value());
    EXPECT_FALSE(t->ran());
    EXPECT_NE(t->reason().find("held: its pipelines are compiling"), std::string::npos) << t->reason();
  }

  // Then the history passes' (the temporal pass): the frame after reuses history, without a reset.
  ASSERT_TRUE(wait_until([&] { return daemon.process().output().find("the pipelines of restir-di compiled: ") != std::string::npos; },
                         170s))
      << "restir-di was not compiled within 170 s: " << daemon.process().output();
  const double compile_s = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  const auto with_history = next_frame();
  ASSERT_TRUE(with_history) << daemon.process().output();
  EXPECT_FALSE(with_history->history_reset()) << with_history->history_reset_reason();
  const auto t = temporal(*with_history);
  ASSERT_TRUE(t.has_value());
  EXPECT_TRUE(t->ran()) << t->reason();
  if (!second_stage_done) {
    EXPECT_NE(daemon.process().output().find("the history passes of restir-di are compiled"), std::string::npos) << daemon.process().output();
  }
  EXPECT_TRUE(stream.close().ok());
  std::printf("progressive start: the first frame by pt, restir-di from the second after %.1f s of compile (temporal held), "
              "its history passes after %.1f s%s\n",
              first_s, compile_s, second_stage_done ? " (already compiled at the second frame)" : "");

  // A second session of the same method and scene finds its pipelines listed: they are created on
  // every core at once before its renderer, and its first frame is restir-di's.
  const v1::Session again = create_ok(*stub, req);
  StreamClient second(*stub);
  ASSERT_TRUE(second.send(frame_input(1, again.name(), 0)));
  const auto frame = second.read();
  ASSERT_TRUE(frame) << daemon.process().output();
  EXPECT_FALSE(compiling(*frame)) << frame->statistics().passes(0).reason();
  EXPECT_TRUE(frame->statistics().has_reuse());
  EXPECT_NE(daemon.process().output().find("compiled pipelines created in"), std::string::npos) << daemon.process().output();
  EXPECT_TRUE(second.close().ok());
}

// A session's start asks whether its method's pipelines are compiled by building the renderer on a
// context that only records them. restir-multilayer with its layer count measured (the default)
// measures the scene with a ray probe while it is built: that probe must not be dispatched on the
// recording context (it crashed the daemon on lavapipe's queue thread), so the session starts, its
// first frame arrives, and the daemon goes on serving.
TEST(WarmUpTest, AMultilayerSessionMeasuringItsLayersStartsProgressively) {
  OpsDaemon daemon({"--progressive-start"});
  auto stub = v1::RenderService::NewStub(loopback_channel(daemon.address()));
  auto req = session_request("cornell", 16, 16);
  req.set_method("restir-multilayer");
  const v1::Session s = create_ok(*stub, req);
  StreamClient stream(*stub);
  ASSERT_TRUE(stream.send(frame_input(1, s.name(), 0))) << daemon.process().output();
  const auto frame = stream.read();
  ASSERT_TRUE(frame) << daemon.process().output();
  EXPECT_GT(frame->images_size(), 0) << daemon.process().output();
  EXPECT_TRUE(stream.close().ok()) << daemon.process().output();
  auto again = session_request("cornell", 16, 16);
  again.set_method("pt");
  create_ok(*stub, again);  // still serving
}

}  // namespace
}  // namespace strata::test
