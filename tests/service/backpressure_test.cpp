// A client that sends inputs but never reads: the server keeps rendering, replaces the waiting
// frame with the newest one and counts the drops; its buffered bytes (and, for a stratad process,
// its resident memory) stay bounded instead of growing with a queue.
#include <signal.h>

#include <cstdio>
#include <cstdlib>

#include "harness.h"
#include "process.h"

namespace strata::test {
namespace {

using BackpressureTest = ServiceTest;

// A client whose transport does not grow its receive window (no BDP probing): what it does not
// read stays on the server's side of a 64 KiB window.
std::unique_ptr<v1::RenderService::Stub> small_window_stub(const std::string& address) {
  grpc::ChannelArguments args;
  args.SetMaxReceiveMessageSize(64 << 20);
  args.SetInt(GRPC_ARG_HTTP2_BDP_PROBE, 0);
  return v1::RenderService::NewStub(grpc::CreateCustomChannel(address, grpc::InsecureChannelCredentials(), args));
}

// Sends `inputs` inputs one at a time, each after the previous one was rendered; never reads.
// `after_each(i)` runs after input i was rendered.
void send_paced(v1::RenderService::Stub& stub, StreamClient& c, const std::string& session, uint64_t inputs,
                const std::function<void(uint64_t)>& after_each) {
  for (uint64_t i = 1; i <= inputs; ++i) {
    ASSERT_TRUE(c.send(frame_input(i, i == 1 ? session : "", uint32_t(i))));
    ASSERT_TRUE(wait_until([&] {
      v1::Session s;
      return get_session(stub, session, &s).ok() && s.frames_rendered() >= i;
    }, 30s)) << "input " << i << " was not rendered";
    after_each(i);
  }
}

TEST_F(BackpressureTest, AClientThatNeverReadsGetsTheNewestFrameAndBoundedServerMemory) {
  constexpr uint32_t w = 256, h = 192;
  constexpr uint64_t inputs = 16;
  const int64_t float_frame = int64_t(w) * h * 16, raw_frame = int64_t(w) * h * 8;
  const v1::Session s = create_ok(stub(), session_request("cornell", w, h));
  auto reader = small_window_stub(address());
  StreamClient c(*reader);
  int64_t max_buffered = 0;
  send_paced(stub(), c, s.name(), inputs, [&](uint64_t) {
    max_buffered = std::max<int64_t>(max_buffered, int64_t(server_status(stub()).buffered_frame_bytes()));
  });
  // At most one frame waits in the slot (float image) and one is being encoded or written.
  EXPECT_LE(max_buffered, 2 * (float_frame + raw_frame)) << "buffered frame bytes grew like a queue";
  v1::Session mid;
  ASSERT_TRUE(get_session(stub(), s.name(), &mid).ok());
  // One frame is being written (the client's window is full), one waits; the rest were replaced.
  EXPECT_GE(mid.frames_dropped(), inputs - 3) << "frames the client could not take must be dropped, not queued";

  // Now read: the newest frame arrives, and the drops are reported with the frames.
  std::vector<v1::Frame> frames;
  const grpc::Status st = c.close(&frames);
  EXPECT_TRUE(st.ok()) << st.error_message();
  ASSERT_FALSE(frames.empty());
  EXPECT_EQ(frames.back().input_sequence(), inputs);
  uint64_t dropped = 0;
  for (const auto& f : frames) dropped += f.frames_dropped();
  v1::Session end;
  ASSERT_TRUE(get_session(stub(), s.name(), &end).ok());
  EXPECT_EQ(dropped, end.frames_dropped());
  EXPECT_EQ(frames.size() + dropped, end.frames_rendered());
  EXPECT_EQ(server_status(stub()).buffered_frame_bytes(), 0u);
}

TEST(BackpressureProcessTest, StratadMemoryStaysFlatWhileAClientDoesNotRead) {
  constexpr uint32_t w = 320, h = 240;
  constexpr uint64_t warmup = 6, inputs = 30;
  const uint64_t raw_frame = uint64_t(w) * h * 8;
#if defined(__SANITIZE_ADDRESS__)
  // AddressSanitizer keeps freed memory in quarantine, which would read as growth.
  setenv("ASAN_OPTIONS", "quarantine_size_mb=0:thread_local_quarantine_size_kb=0", 1);
#endif
  Daemon daemon({"--max-pixels", std::to_string(w * h)});
  auto stub = v1::RenderService::NewStub(loopback_channel(daemon.address()));
  const v1::Session s = create_ok(*stub, session_request("cornell", w, h));
  auto reader = small_window_stub(daemon.address());
  StreamClient c(*reader);
  uint64_t rss_after_warmup = 0, rss_max = 0;
  send_paced(*stub, c, s.name(), inputs, [&](uint64_t i) {
    const uint64_t rss = daemon.process().rss_bytes();
    if (i == warmup) rss_after_warmup = rss;
    if (i > warmup) rss_max = std::max(rss_max, rss);
  });
  ASSERT_GT(rss_after_warmup, 0u);
  const int64_t growth = int64_t(rss_max) - int64_t(rss_after_warmup);
  std::printf("stratad RSS after %llu frames: %llu bytes; largest over the next %llu: %llu bytes (growth %lld)\n",
              static_cast<unsigned long long>(warmup), static_cast<unsigned long long>(rss_after_warmup),
              static_cast<unsigned long long>(inputs - warmup), static_cast<unsigned long long>(rss_max),
              static_cast<long long>(growth));
  // A queue would hold (inputs - warmup) more frames: 24 x 1.2 MB (float) or 0.6 MB (encoded).
  EXPECT_LT(growth, int64_t(8 * raw_frame)) << "stratad grew by " << growth << " bytes over " << inputs - warmup << " frames";
  v1::Session mid;
  ASSERT_TRUE(get_session(*stub, s.name(), &mid).ok());
  EXPECT_GE(mid.frames_dropped(), inputs - 3);
  c.cancel();
  EXPECT_FALSE(c.finish().ok());
  daemon.process().signal(SIGTERM);
  EXPECT_EQ(daemon.process().wait_exit(30s), std::optional<int>(0)) << daemon.process().output();
}

}  // namespace
}  // namespace strata::test
