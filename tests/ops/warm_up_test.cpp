// stratad serve --warm-up on a cold machine (Mesa's shader cache pointed at an empty folder): the
// restir-gather pipelines are compiled at start (/readyz answers 503 "warming pipelines" meanwhile
// and 200 after, a log line counts them, Mesa's cache fills), and a session's first frame then
// finds them compiled: it renders in a fraction of the compile time. GALLIVM_PERF=nopt (llvmpipe
// without LLVM's optimisation passes) keeps the compile, and so the test, about twice as short.
#include <gtest/gtest.h>

#include <cstdlib>

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

}  // namespace
}  // namespace strata::test
