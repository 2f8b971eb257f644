// The Prometheus page of a live stratad (--metrics-listen) after real traffic: Debian's promtool
// accepts it (`promtool check metrics`: names, units, _total, help), the frame, pass, reset,
// shift-failure and gRPC series count what happened, and no session id appears in it.
#include <gtest/gtest.h>

#include "harness.h"
#include "ops_util.h"

namespace strata::test {
namespace {

TEST(MetricsTest, LivePagePassesPromtoolAndCountsTheTraffic) {
  TempDir dir;
  OpsDaemon daemon({"--metrics-listen", "127.0.0.1:0", "--max-sessions", "3"});
  auto stub = v1::RenderService::NewStub(loopback_channel(daemon.address()));

  const v1::Session pt = create_ok(*stub, session_request("cornell", 16, 16));
  auto restir_req = session_request("cornell", 16, 16);
  restir_req.set_method("restir-gather");
  const v1::Session restir = create_ok(*stub, restir_req);
  const v1::Session third = create_ok(*stub, session_request("cornell", 16, 16));
  v1::Session refused;
  EXPECT_EQ(create_session(*stub, session_request("cornell", 16, 16), &refused).error_code(), grpc::StatusCode::RESOURCE_EXHAUSTED);
  auto bad = session_request("cornell", 16, 16);
  bad.set_method("no-such-method");
  EXPECT_EQ(create_session(*stub, bad, &refused).error_code(), grpc::StatusCode::INVALID_ARGUMENT);
  ASSERT_EQ(stream_frames(*stub, pt.name(), 3).size(), 3u);
  ASSERT_EQ(stream_frames(*stub, restir.name(), 3).size(), 3u);

  // Device memory exists while a session streams (a stream's end releases it).
  uint64_t background_frames = 0;
  {
    BackgroundStream bg(daemon.address(), third.name());
    ASSERT_TRUE(wait_until([&] { return bg.frames() > 0; }, 60s));
    const HttpResponse during = http_get(daemon.metrics_address(), "/metrics");
    EXPECT_NE(during.body.find("strata_device_memory_bytes{group="), std::string::npos) << during.body;
    EXPECT_EQ(sample_value(during.body, "strata_streams_active"), 1.0);
    EXPECT_TRUE(bg.stop().ok());
    background_frames = bg.frames();
  }

  // The interceptor counts a call once gRPC is done with it, a moment after the client has its status.
  const std::string streams_ok =
      R"(grpc_server_handled_total{grpc_code="OK",grpc_method="Stream",grpc_service="strata.v1.RenderService",grpc_type="bidi_stream"})";
  HttpResponse r;
  EXPECT_TRUE(wait_until([&] {
    r = http_get(daemon.metrics_address(), "/metrics");
    return sample_value(r.body, streams_ok) == 3.0;
  }, 10s)) << "three streams ended OK";
  ASSERT_EQ(r.status, 200) << r.headers;
  const std::string& page = r.body;
  write_text(dir.path / "metrics.txt", page);

  // promtool reads the page on stdin and prints every problem; nothing printed, exit 0: clean.
  const std::string promtool = tool_path("STRATA_PROMTOOL", "/usr/bin/promtool");
  const auto check = run_process({"/bin/sh", "-c", promtool + " check metrics < " + (dir.path / "metrics.txt").string()}, 60s);
  EXPECT_EQ(check.exit_code, 0) << "promtool check metrics:\n" << check.output;
  EXPECT_EQ(check.output.find("problem"), std::string::npos) << check.output;

  EXPECT_EQ(sample_value(page, R"(strata_frames_rendered_total{method="pt"})"), double(3 + background_frames)) << page;
  EXPECT_EQ(sample_value(page, R"(strata_frames_rendered_total{method="restir-gather"})"), 3.0);
  EXPECT_EQ(sample_value(page, R"(strata_frame_latency_seconds_count{method="restir-gather"})"), 3.0);
  EXPECT_EQ(sample_value(page, R"(strata_history_resets_total{reason="first_frame"})"), 3.0);
  EXPECT_EQ(sample_value(page, "strata_frame_observer_seconds_count"), double(6 + background_frames)) << "every frame timed";
  EXPECT_EQ(sample_value(page, R"(strata_frame_render_seconds_count{method="restir-gather"})"), 3.0);
  EXPECT_EQ(sample_value(page, R"(strata_history_resets_total{reason="gpu_state_released"})"), -1.0) << "no stream was resumed";
  EXPECT_EQ(sample_value(page, "strata_sessions_created_total"), 3.0);
  EXPECT_EQ(sample_value(page, "strata_sessions_active"), 3.0);
  EXPECT_EQ(sample_value(page, "strata_frames_dropped_total"), 0.0);
  EXPECT_GE(sample_value(page, "strata_disoccluded_pixels_total"), 0.0);
  EXPECT_GT(sample_value(page, R"(strata_rays_traced_total{method="pt"})"), 0.0);
  EXPECT_NE(page.find("strata_frame_pass_gpu_seconds_bucket{pass="), std::string::npos);
  EXPECT_NE(page.find("strata_shift_failures_total{pass=\"temporal\""), std::string::npos) << "restir-gather reported no shift failures";
  EXPECT_NE(page.find("strata_build_info{"), std::string::npos);
  EXPECT_EQ(sample_value(page, R"(grpc_server_handled_total{grpc_code="OK",grpc_method="CreateSession",grpc_service="strata.v1.RenderService",grpc_type="unary"})"), 3.0);
  EXPECT_EQ(sample_value(page, R"(grpc_server_handled_total{grpc_code="ResourceExhausted",grpc_method="CreateSession",grpc_service="strata.v1.RenderService",grpc_type="unary"})"), 1.0);
  EXPECT_EQ(sample_value(page, R"(grpc_server_handled_total{grpc_code="InvalidArgument",grpc_method="CreateSession",grpc_service="strata.v1.RenderService",grpc_type="unary"})"), 1.0);
  // No session id as a label (unbounded cardinality).
  for (const auto& s : {pt, restir, third}) EXPECT_EQ(page.find(s.name().substr(9)), std::string::npos) << s.name();
}

TEST(MetricsTest, BadMetricsListenNamesTheFlag) {
  const auto r = run_process({stratad_path(), "serve", "--listen", "127.0.0.1:0", "--metrics-listen", "127.0.0.1:notaport"}, 60s);
  EXPECT_NE(r.exit_code, 0);
  EXPECT_NE(r.output.find("--metrics-listen"), std::string::npos) << r.output;
}

}  // namespace
}  // namespace strata::test
