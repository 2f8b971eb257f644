// Graceful drain: health goes NOT_SERVING, new sessions and streams are refused with UNAVAILABLE,
// frames whose input had arrived are finished and sent, streams end with UNAVAILABLE, and the
// server stops (stratad exits 0 on SIGTERM).
#include <signal.h>

#include <algorithm>
#include <atomic>
#include <mutex>

#include "grpc/health/v1/health.grpc.pb.h"
#include "harness.h"
#include "process.h"

namespace strata::test {
namespace {

using grpc::health::v1::HealthCheckResponse;
using DrainTest = ServiceTest;

HealthCheckResponse::ServingStatus health(const std::string& address) {
  auto stub = grpc::health::v1::Health::NewStub(loopback_channel(address));
  grpc::ClientContext ctx;
  ctx.set_deadline(std::chrono::system_clock::now() + 5s);
  HealthCheckResponse resp;
  if (!stub->Check(&ctx, {}, &resp).ok()) return HealthCheckResponse::UNKNOWN;
  return resp.status();
}

// Waits until the server has received input `sequence` of `session`.
bool input_arrived(v1::RenderService::Stub& stub, const std::string& session, uint64_t sequence) {
  return wait_until([&] {
    v1::Session s;
    return get_session(stub, session, &s).ok() && s.last_input_sequence() >= sequence;
  }, 10s);
}

TEST_F(DrainTest, DrainRefusesNewWorkFinishesFramesInFlightAndStops) {
  // A client that does not read holds a frame write open, which keeps the drain going for
  // drain_timeout; meanwhile everything new is refused.
  grpc::ChannelArguments args;
  args.SetMaxReceiveMessageSize(64 << 20);
  args.SetInt(GRPC_ARG_HTTP2_BDP_PROBE, 0);
  auto stuck_stub = v1::RenderService::NewStub(grpc::CreateCustomChannel(address(), grpc::InsecureChannelCredentials(), args));
  const v1::Session stuck = create_ok(stub(), session_request("cornell", 256, 192));
  StreamClient stuck_stream(*stuck_stub);
  for (uint64_t i = 1; i <= 2; ++i) {
    ASSERT_TRUE(stuck_stream.send(frame_input(i, i == 1 ? stuck.name() : "", 0)));
    ASSERT_TRUE(wait_until([&] {
      v1::Session s;
      return get_session(stub(), stuck.name(), &s).ok() && s.frames_rendered() >= i;
    }, 30s));
  }

  const v1::Session live = create_ok(stub(), session_request("cornell", 32, 24));
  StreamClient stream(stub());
  ASSERT_TRUE(stream.send(frame_input(1, live.name(), 0)));
  ASSERT_TRUE(stream.read());
  ASSERT_TRUE(stream.send(frame_input(2, "", 1)));
  ASSERT_TRUE(input_arrived(stub(), live.name(), 2));

  ASSERT_EQ(health(address()), HealthCheckResponse::SERVING);
  std::thread drain([&] { server_->drain(); });

  // The frame whose input had arrived is delivered, then the stream ends with UNAVAILABLE.
  auto f = stream.read();
  ASSERT_TRUE(f);
  EXPECT_EQ(f->input_sequence(), 2u);
  EXPECT_FALSE(stream.read());
  grpc::Status st = stream.finish();
  EXPECT_EQ(st.error_code(), grpc::StatusCode::UNAVAILABLE);
  EXPECT_NE(st.error_message().find("draining"), std::string::npos) << st.error_message();

  // While the stuck stream holds the drain open: NOT_SERVING, new work refused, reads still work.
  EXPECT_EQ(health(address()), HealthCheckResponse::NOT_SERVING);
  v1::Session refused;
  st = create_session(stub(), session_request("cornell", 16, 16), &refused);
  EXPECT_EQ(st.error_code(), grpc::StatusCode::UNAVAILABLE);
  EXPECT_NE(st.error_message().find("draining"), std::string::npos) << st.error_message();
  StreamClient late(stub());
  late.send(frame_input(1, live.name(), 0));
  EXPECT_FALSE(late.read());
  st = late.finish();
  EXPECT_EQ(st.error_code(), grpc::StatusCode::UNAVAILABLE);
  EXPECT_NE(st.error_message().find("draining"), std::string::npos) << st.error_message();
  EXPECT_TRUE(server_status(stub()).draining());

  drain.join();  // the stuck stream was cancelled after drain_timeout
  stuck_stream.cancel();
  EXPECT_FALSE(stuck_stream.finish().ok());
}

TEST(DrainProcessTest, SigtermFinishesTheFrameInFlightAndExitsZero) {
  Daemon daemon({"--drain-timeout", "20"});
  auto stub = v1::RenderService::NewStub(loopback_channel(daemon.address()));

  // Watch health from before the signal.
  std::mutex mu;
  std::vector<HealthCheckResponse::ServingStatus> seen;
  auto health_stub = grpc::health::v1::Health::NewStub(loopback_channel(daemon.address()));
  grpc::ClientContext watch_ctx;
  watch_ctx.set_deadline(std::chrono::system_clock::now() + 60s);
  auto watch = health_stub->Watch(&watch_ctx, {});
  std::thread watcher([&] {
    HealthCheckResponse r;
    while (watch->Read(&r)) {
      std::lock_guard lock(mu);
      seen.push_back(r.status());
    }
    watch->Finish();
  });
  ASSERT_TRUE(wait_until([&] {
    std::lock_guard lock(mu);
    return !seen.empty();
  }, 10s));

  const v1::Session s = create_ok(*stub, session_request("cornell", 128, 96));
  StreamClient stream(*stub);
  ASSERT_TRUE(stream.send(frame_input(1, s.name(), 0)));
  ASSERT_TRUE(stream.read());
  v1::FrameInput heavy = frame_input(2, "", 1);
  heavy.mutable_options()->set_spp(32);  // a frame that takes a while
  ASSERT_TRUE(stream.send(heavy));
  ASSERT_TRUE(input_arrived(*stub, s.name(), 2));
  daemon.process().signal(SIGTERM);

  auto f = stream.read();
  ASSERT_TRUE(f) << "the frame in flight was not delivered";
  EXPECT_EQ(f->input_sequence(), 2u);
  EXPECT_EQ(f->statistics().paths(), 128u * 96u * 32u);
  EXPECT_FALSE(stream.read());
  const grpc::Status st = stream.finish();
  EXPECT_EQ(st.error_code(), grpc::StatusCode::UNAVAILABLE);
  EXPECT_NE(st.error_message().find("draining"), std::string::npos) << st.error_message();

  EXPECT_EQ(daemon.process().wait_exit(30s), std::optional<int>(0)) << daemon.process().output();
  watcher.join();
  {
    std::lock_guard lock(mu);
    ASSERT_FALSE(seen.empty());
    EXPECT_EQ(seen.front(), HealthCheckResponse::SERVING);
    EXPECT_NE(std::find(seen.begin(), seen.end(), HealthCheckResponse::NOT_SERVING), seen.end());
  }
  v1::Session after;
  EXPECT_EQ(create_session(*stub, session_request("cornell", 16, 16), &after).error_code(), grpc::StatusCode::UNAVAILABLE);
  const std::string log = daemon.process().output();
  EXPECT_NE(log.find("draining"), std::string::npos) << log;
  EXPECT_NE(log.find("stopped"), std::string::npos) << log;
}

}  // namespace
}  // namespace strata::test
