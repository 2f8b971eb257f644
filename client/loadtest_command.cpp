// `strata loadtest`: many sessions streaming from stratad at once, shaped after ghz: -c sessions,
// -n frames or -z seconds, --rps pacing (latency from each frame's scheduled send time) or a
// step/line schedule, --connections channels. Writes report.json (a superset of ghz's report),
// report.html and a summary on stdout into --out; every loop is bounded in count and time.
#include <algorithm>
#include <chrono>
#include <climits>
#include <ctime>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <memory>
#include <thread>

#include "camera_path.h"
#include "commands.h"
#include "connection.h"
#include "loadtest_html.h"
#include "loadtest_options.h"
#include "loadtest_pacer.h"
#include "loadtest_progress.h"
#include "loadtest_report.h"
#include "loadtest_session.h"
#include "strata/v1/render.grpc.pb.h"

namespace strata::client {
namespace {

namespace fs = std::filesystem;

v1::CreateSessionRequest session_request(const LoadtestOptions& o) {
  v1::CreateSessionRequest req;
  req.mutable_scene()->set_builtin(o.scene);
  req.mutable_resolution()->set_width(o.width);
  req.mutable_resolution()->set_height(o.height);
  req.set_method(o.method);
  req.set_seed(o.seed);
  req.mutable_options()->set_spp(o.spp);
  set_restir_options(o.restir, *req.mutable_options());
  for (auto e : parse_encoding_list(o.encodings)) req.add_encodings(e);
  return req;
}

// One channel per --connections; a distinct argument keeps gRPC from sharing one connection.
std::shared_ptr<grpc::Channel> channel(const std::string& server, uint64_t max_frame_bytes, int index) {
  grpc::ChannelArguments args;
  args.SetMaxReceiveMessageSize(int(std::min<uint64_t>(max_frame_bytes, INT_MAX)));
  args.SetInt("strata.loadtest_connection", index);
  args.SetInt(GRPC_ARG_USE_LOCAL_SUBCHANNEL_POOL, 1);
  return grpc::CreateCustomChannel(server, grpc::InsecureChannelCredentials(), args);
}

std::string now_rfc3339() {
  const std::time_t t = std::time(nullptr);
  std::tm tm{};
  gmtime_r(&t, &tm);
  char buf[32];
  std::strftime(buf, sizeof buf, "%Y-%m-%dT%H:%M:%SZ", &tm);
  return buf;
}

void print_summary(const nlohmann::json& r, const fs::path& out) {
  const auto& s = r["strata"];
  const auto& f = s["frames"];
  auto ms = [](int64_t ns) { return double(ns) / 1e6; };
  std::printf("\nSummary: %s\n", r["name"].get<std::string>().c_str());
  std::printf("  Count:        %llu frames requested\n", (unsigned long long)r["count"].get<uint64_t>());
  std::printf("  Total:        %.2f s\n", double(r["total"].get<int64_t>()) / 1e9);
  std::printf("  Slowest:      %.2f ms\n  Fastest:      %.2f ms\n  Average:      %.2f ms\n", ms(r["slowest"].get<int64_t>()),
              ms(r["fastest"].get<int64_t>()), ms(r["average"].get<int64_t>()));
  std::printf("  Requests/sec: %.2f\n  Frames/sec:   %.2f\n", r["rps"].get<double>(), s["frames_per_second"].get<double>());
  std::printf("  Frames:       sent %llu = received %llu + dropped %llu + coalesced %llu + errors %llu\n",
              (unsigned long long)f["inputs_sent"].get<uint64_t>(), (unsigned long long)f["frames_received"].get<uint64_t>(),
              (unsigned long long)f["frames_dropped"].get<uint64_t>(), (unsigned long long)f["inputs_coalesced"].get<uint64_t>(),
              (unsigned long long)f["errors"].get<uint64_t>());
  std::printf("  Time to first frame p50: %.1f ms, inter-frame gap p99: %.1f ms, server GPU mean: %.2f ms, history resets: %llu\n",
              s["time_to_first_frame_ms"]["p50"].get<double>(), s["inter_frame_gap_ms"]["p99"].get<double>(),
              s["server_gpu_ms"]["mean"].get<double>(), (unsigned long long)s["history_resets"].get<uint64_t>());
  std::printf("  Session create p50: %.1f ms, delete p50: %.1f ms\n", s["create_session_ms"]["p50"].get<double>(),
              s["delete_session_ms"]["p50"].get<double>());
  std::printf("\nLatency distribution:\n");
  for (const auto& d : r["latencyDistribution"])
    std::printf("  %5.1f %% in %.2f ms\n", d["percentage"].get<double>(), ms(d["latency"].get<int64_t>()));
  std::printf("\nStatus code distribution (frames):\n");
  for (const auto& [code, n] : r["statusCodeDistribution"].items()) std::printf("  [%s] %llu\n", code.c_str(), (unsigned long long)n.get<uint64_t>());
  std::printf("\nRPC status codes:\n");
  for (const auto& [method, codes] : s["rpcStatusCodes"].items())
    for (const auto& [code, n] : codes.items()) std::printf("  %s [%s] %llu\n", method.c_str(), code.c_str(), (unsigned long long)n.get<uint64_t>());
  if (!r["errorDistribution"].empty()) {
    std::printf("\nError distribution:\n");
    for (const auto& [e, n] : r["errorDistribution"].items()) std::printf("  [%llu] %s\n", (unsigned long long)n.get<uint64_t>(), e.c_str());
  }
  std::printf("\nwrote %s and %s\n", (out / "report.json").c_str(), (out / "report.html").c_str());
}

int run_loadtest(LoadtestOptions& o) {
  o.validate();
  const auto script = o.camera_path.empty() ? std::vector<v1::FrameInput>{} : load_camera_path(o.camera_path);
  const v1::CreateSessionRequest request = session_request(o);

  v1::ServerStatus status;
  {
    auto stub = v1::RenderService::NewStub(connect(o.server));
    grpc::ClientContext ctx;
    set_deadline(ctx, std::chrono::milliseconds(int64_t(o.timeout_s * 1000.0)));
    const auto st = stub->GetServerStatus(&ctx, {}, &status);
    if (!st.ok()) throw RpcError("GetServerStatus (" + o.server + ")", st);
  }
  std::vector<std::shared_ptr<grpc::Channel>> channels;
  for (uint32_t i = 0; i < o.connections; ++i) channels.push_back(channel(o.server, status.limits().max_frame_bytes(), int(i)));
  fs::create_directories(o.out);
  std::cerr << "strata loadtest: " << o.concurrency << " session(s) of '" << o.scene << "' " << o.method << " " << o.width << "x"
            << o.height << " over " << o.connections << " connection(s) to " << o.server << " (" << status.device() << ")\n";

  RunInfo run;
  run.date = now_rfc3339();
  run.device = status.device();
  run.start = LoadClock::now();
  Pacer pacer(o, run.start);
  LoadProgress counters;
  std::vector<SessionResult> results(o.concurrency);
  {
    LoadtestProgress progress(o, counters, run.start);
    std::vector<std::thread> threads;
    for (uint32_t i = 0; i < o.concurrency; ++i)
      threads.emplace_back([&, i] { results[i] = run_session(o, request, script, channels[i % channels.size()], pacer, counters, i); });
    for (auto& t : threads) t.join();
  }
  run.end = LoadClock::now();

  const nlohmann::json report = make_report(o, run, results);
  {
    std::ofstream out(fs::path(o.out) / "report.json");
    out << report.dump(2) << "\n";
    if (!out) throw std::runtime_error("cannot write " + (fs::path(o.out) / "report.json").string());
  }
  write_loadtest_html(report, fs::path(o.out) / "report.html");
  print_summary(report, o.out);
  return 0;
}

}  // namespace

Runner add_loadtest_command(CLI::App& app) {
  auto o = std::make_shared<LoadtestOptions>();
  auto* cmd = app.add_subcommand("loadtest", "load-test stratad with many streaming sessions (ghz-like); report.json and report.html in --out");
  cmd->add_option("--server", o->server, "stratad address host:port")->capture_default_str();
  cmd->add_option("-c,--concurrency", o->concurrency, "sessions streaming at once (1..64)")->capture_default_str();
  cmd->add_option("-n,--total", o->total, "frames to request over every session (at most 1000000)");
  cmd->add_option("-z,--duration", o->duration_s, "seconds to run (at most 3600); with -n, whichever ends first");
  cmd->add_option("--rps", o->rps, "frames per second over every session, paced; latency counts from each frame's scheduled send time (0: each session sends its next input when a frame arrives)")
      ->capture_default_str();
  cmd->add_option("--connections", o->connections, "gRPC connections the sessions share round-robin (1..concurrency)")->capture_default_str();
  cmd->add_option("--timeout", o->timeout_s, "seconds a unary call, or a frame's input, may wait for its answer")->capture_default_str();
  cmd->add_option("--skip-first", o->skip_first, "frames of each session left out of the latency statistics (warm-up)")->capture_default_str();
  cmd->add_option("--load-schedule", o->schedule.kind, "const (--rps) | step | line")->capture_default_str();
  cmd->add_option("--load-start", o->schedule.start, "step/line: frames/s at the start");
  cmd->add_option("--load-step", o->schedule.step, "step: frames/s added per step; line: frames/s added per second");
  cmd->add_option("--load-end", o->schedule.end, "step/line: the rate it stops changing at (0: none)");
  cmd->add_option("--load-step-duration", o->schedule.step_duration_s, "step: seconds per step")->capture_default_str();
  cmd->add_option("--name", o->name, "the report's name");
  cmd->add_option("--tags", o->tags, "key=value tags recorded in the report (repeatable)");
  cmd->add_flag("--details", o->details, "record every frame request in report.json's details");
  cmd->add_option("--out", o->out, "output directory")->capture_default_str();
  cmd->add_option("--scene", o->scene, "built-in scene name")->capture_default_str();
  cmd->add_option("--method", o->method, "rendering method (pt, restir-gather, ...)")->capture_default_str();
  cmd->add_option("--width", o->width, "image width")->capture_default_str();
  cmd->add_option("--height", o->height, "image height")->capture_default_str();
  cmd->add_option("--spp", o->spp, "samples per pixel per frame")->capture_default_str();
  cmd->add_option("--seed", o->seed, "random seed")->capture_default_str();
  cmd->add_option("--encodings", o->encodings, "images to request: exr, raw, png, domain (the domain map of restir-multilayer; comma-separated)")->capture_default_str();
  cmd->add_option("--camera-path", o->camera_path, "JSON script of FrameInputs, replayed in a loop (see client/camera_path.h)");
  add_restir_flags(cmd, o->restir);
  return [o] { return run_loadtest(*o); };
}

}  // namespace strata::client
