// strata_service_bench: what gRPC costs per frame. For the same frames of the same scene (same
// seed), it measures in one run
//   - in-process: Renderer::render (as `stratad render` does), and the CPU cost of each encoding;
//   - through gRPC: the latency from sending a FrameInput to receiving its Frame, lockstep, from a
//     client on 127.0.0.1 to the service running in this process on the same device;
// and writes JSON plus a Markdown table (docs/BENCHMARKS.md). Lavapipe compiles shaders at first
// dispatch, so every series starts with warm-up frames that are not counted.
#include <CLI/CLI.hpp>
#include <algorithm>
#include <chrono>
#include <cstdio>
#include <fstream>
#include <iostream>
#include <map>
#include <nlohmann/json.hpp>

#include <grpcpp/grpcpp.h>

#include "gpu/context.h"
#include "render/renderer.h"
#include "scene/scene_io.h"
#include "service/encoding.h"
#include "service/input_checks.h"
#include "service/server.h"
#include "strata/v1/render.grpc.pb.h"
#include "util/summary.h"

namespace {

namespace v1 = strata::v1;
using Clock = std::chrono::steady_clock;

struct Args {
  std::string scene = "cornell";
  uint32_t width = 256, height = 192, spp = 1, frames = 30, warmup = 3, seed = 1;
  std::string out = "bench_service.json";
  std::string device;
};

using Stats = strata::util::Summary;
Stats stats_of(std::vector<double> v) { return strata::util::summarize(std::move(v)); }

nlohmann::json to_json(const Stats& s) { return {{"mean", s.mean}, {"p50", s.p50}, {"p95", s.p95}}; }

double ms_since(Clock::time_point t) { return std::chrono::duration<double, std::milli>(Clock::now() - t).count(); }

const std::vector<std::pair<std::string, std::vector<v1::ImageEncoding>>>& encoding_sets() {
  static const std::vector<std::pair<std::string, std::vector<v1::ImageEncoding>>> sets = {
      {"raw", {v1::IMAGE_ENCODING_RAW_RGBA16F}},
      {"exr", {v1::IMAGE_ENCODING_EXR_HALF}},
      {"png", {v1::IMAGE_ENCODING_PNG_PREVIEW}},
      {"exr+png", {v1::IMAGE_ENCODING_EXR_HALF, v1::IMAGE_ENCODING_PNG_PREVIEW}},
  };
  return sets;
}

struct InProcess {
  std::vector<double> render_ms;
  std::map<v1::ImageEncoding, std::vector<double>> encode_ms;
};

InProcess run_in_process(const strata::gpu::Context& ctx, const Args& a) {
  const strata::scene::Scene scene = strata::scene::builtin_scene(a.scene);
  strata::render::RenderSettings rs;
  rs.width = a.width;
  rs.height = a.height;
  rs.spp = a.spp;
  rs.seed = a.seed;
  strata::render::Renderer renderer(ctx, scene, rs);
  InProcess r;
  for (uint32_t f = 0; f < a.warmup + a.frames; ++f) {
    const auto t0 = Clock::now();
    strata::render::FrameResult fr = renderer.render(scene.frame_state(f), f);
    const double ms = ms_since(t0);
    if (f < a.warmup) continue;
    r.render_ms.push_back(ms);
    for (auto e : {v1::IMAGE_ENCODING_RAW_RGBA16F, v1::IMAGE_ENCODING_EXR_HALF, v1::IMAGE_ENCODING_PNG_PREVIEW}) {
      const auto t1 = Clock::now();
      const v1::Image img = strata::service::encode_image(fr.image, e, 0.0f);
      r.encode_ms[e].push_back(ms_since(t1));
      if (img.data().empty()) throw std::runtime_error("empty encoding");
    }
  }
  return r;
}

struct Remote {
  std::vector<double> latency_ms, server_render_ms, server_encode_ms;
  uint64_t bytes = 0;
};

Remote run_grpc(v1::RenderService::Stub& stub, const Args& a, const std::vector<v1::ImageEncoding>& encodings) {
  v1::CreateSessionRequest req;
  req.mutable_scene()->set_builtin(a.scene);
  req.mutable_resolution()->set_width(a.width);
  req.mutable_resolution()->set_height(a.height);
  req.set_method("pt");  // as the in-process renderer (RenderSettings' method), not the session default auto
  req.mutable_options()->set_spp(a.spp);
  req.set_seed(a.seed);
  for (auto e : encodings) req.add_encodings(e);
  v1::Session session;
  {
    grpc::ClientContext ctx;
    auto st = stub.CreateSession(&ctx, req, &session);
    if (!st.ok()) throw std::runtime_error("CreateSession: " + st.error_message());
  }
  Remote r;
  grpc::ClientContext ctx;
  ctx.set_deadline(std::chrono::system_clock::now() + std::chrono::minutes(30));
  auto stream = stub.Stream(&ctx);
  for (uint32_t f = 0; f < a.warmup + a.frames; ++f) {
    v1::FrameInput in;
    if (f == 0) in.set_session(session.name());
    in.set_sequence(f + 1);
    in.set_animation_frame(f);
    const auto t0 = Clock::now();
    v1::Frame frame;
    if (!stream->Write(in) || !stream->Read(&frame)) throw std::runtime_error("the stream ended early");
    const double ms = ms_since(t0);
    if (f < a.warmup) continue;
    r.latency_ms.push_back(ms);
    r.server_render_ms.push_back(frame.timing().render_ms());
    r.server_encode_ms.push_back(frame.timing().encode_ms());
    r.bytes = frame.ByteSizeLong();
  }
  stream->WritesDone();
  auto st = stream->Finish();
  if (!st.ok()) throw std::runtime_error("Stream: " + st.error_message());
  grpc::ClientContext del_ctx;
  v1::DeleteSessionRequest del;
  del.set_name(session.name());
  google::protobuf::Empty empty;
  stub.DeleteSession(&del_ctx, del, &empty);
  return r;
}

int run(const Args& a) {
  strata::gpu::Context ctx({a.device, false});
  strata::service::ServiceConfig cfg;
  cfg.listen = "127.0.0.1:0";
  cfg.limits.max_pixels = std::max<uint64_t>(cfg.limits.max_pixels, uint64_t(a.width) * a.height);
  strata::service::Server server(ctx, cfg);
  grpc::ChannelArguments args;
  args.SetMaxReceiveMessageSize(int(strata::service::max_frame_bytes(cfg.limits.max_pixels)));
  auto stub = v1::RenderService::NewStub(grpc::CreateCustomChannel(server.address(), grpc::InsecureChannelCredentials(), args));

  const InProcess local = run_in_process(ctx, a);
  const Stats render = stats_of(local.render_ms);
  nlohmann::json doc;
  doc["device"] = ctx.device_name();
  doc["scene"] = a.scene;
  doc["width"] = a.width;
  doc["height"] = a.height;
  doc["spp"] = a.spp;
  doc["frames"] = a.frames;
  doc["warmup"] = a.warmup;
  doc["in_process"]["render_ms"] = to_json(render);
  for (const auto& [e, v] : local.encode_ms) doc["in_process"]["encode_ms"][strata::service::encoding_name(e)] = to_json(stats_of(v));

  std::printf("%s, %ux%u, %u spp, %u frames (after %u warm-up), %s\n\n", a.scene.c_str(), a.width, a.height, a.spp, a.frames,
              a.warmup, ctx.device_name().c_str());
  std::printf("| encoding | frame bytes | in-process render+encode p50 ms | gRPC latency p50 ms | gRPC p95 ms | server render p50 ms | server encode p50 ms | transport p50 ms | ratio gRPC / in-process |\n");
  std::printf("|---|---:|---:|---:|---:|---:|---:|---:|---:|\n");
  for (const auto& [name, encodings] : encoding_sets()) {
    const Remote remote = run_grpc(*stub, a, encodings);
    std::vector<double> local_total(local.render_ms);
    for (auto e : encodings)
      for (size_t i = 0; i < local_total.size(); ++i) local_total[i] += local.encode_ms.at(e)[i];
    std::vector<double> transport;
    for (size_t i = 0; i < remote.latency_ms.size(); ++i)
      transport.push_back(remote.latency_ms[i] - remote.server_render_ms[i] - remote.server_encode_ms[i]);
    const Stats lt = stats_of(local_total), lat = stats_of(remote.latency_ms), sr = stats_of(remote.server_render_ms),
                se = stats_of(remote.server_encode_ms), tr = stats_of(transport);
    const double ratio = lat.p50 / lt.p50;
    doc["grpc"][name] = {{"frame_bytes", remote.bytes},
                         {"in_process_render_plus_encode_ms", to_json(lt)},
                         {"latency_ms", to_json(lat)},
                         {"server_render_ms", to_json(sr)},
                         {"server_encode_ms", to_json(se)},
                         {"transport_ms", to_json(tr)},
                         {"ratio_latency_to_in_process_p50", ratio},
                         {"ratio_latency_to_render_only_p50", lat.p50 / render.p50}};
    std::printf("| %s | %llu | %.2f | %.2f | %.2f | %.2f | %.2f | %.2f | %.2f |\n", name.c_str(),
                static_cast<unsigned long long>(remote.bytes), lt.p50, lat.p50, lat.p95, sr.p50, se.p50, tr.p50, ratio);
  }
  std::printf("\nin-process render only: p50 %.2f ms, mean %.2f ms; encode p50:", render.p50, render.mean);
  for (const auto& [e, v] : local.encode_ms) std::printf(" %s %.2f ms", strata::service::encoding_name(e).c_str(), stats_of(v).p50);
  std::printf("\n");
  std::ofstream(a.out) << doc.dump(2) << "\n";
  std::cout << "wrote " << a.out << "\n";
  server.shutdown();
  return 0;
}

}  // namespace

int main(int argc, char** argv) {
  Args a;
  CLI::App app{"strata_service_bench: per-frame latency through gRPC vs in-process rendering, and encode cost"};
  app.add_option("--scene", a.scene, "built-in scene")->capture_default_str();
  app.add_option("--width", a.width)->capture_default_str();
  app.add_option("--height", a.height)->capture_default_str();
  app.add_option("--spp", a.spp)->capture_default_str();
  app.add_option("--frames", a.frames, "measured frames per series")->capture_default_str();
  app.add_option("--warmup", a.warmup, "frames rendered first and not counted")->capture_default_str();
  app.add_option("--seed", a.seed)->capture_default_str();
  app.add_option("--out", a.out, "JSON output")->capture_default_str();
  app.add_option("--device", a.device, "Vulkan device name substring");
  CLI11_PARSE(app, argc, argv);
  try {
    return run(a);
  } catch (const std::exception& e) {
    std::cerr << "strata_service_bench: " << e.what() << "\n";
    return 1;
  }
}
