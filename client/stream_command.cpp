// `strata stream`: creates a session on stratad, plays the scene's default animation (or a
// camera/transform/LoD script) frame by frame over Stream, writes EXR + PNG per frame and
// frames.json with what the server returned, and deletes the session.
#include <algorithm>
#include <chrono>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <map>
#include <memory>
#include <optional>
#include <sstream>

#include <nlohmann/json.hpp>

#include "camera_path.h"
#include "commands.h"
#include "connection.h"
#include "connection_options.h"
#include "frame_files.h"
#include "loadtest_options.h"  // parse_encoding_list, shared with loadtest
#include "progress.h"
#include "restir_flags.h"
#include "strata/v1/render.grpc.pb.h"
#include "util/summary.h"

namespace strata::client {
namespace {

namespace fs = std::filesystem;
namespace v1 = strata::v1;
using Clock = std::chrono::steady_clock;

struct StreamArgs {
  ConnectionOptions conn;  // --server, TLS, token
  std::string session_id;  // empty: a fresh one (new_session_id)
  std::string scene = "cornell";
  std::string scene_file;  // a local .glb sent inline
  std::string scene_path;  // a file in the server's scene directory
  std::string environment_file;  // a local .hdr/.exr sent inline
  std::string environment_path;  // a .hdr/.exr in the server's scene directory
  std::optional<float> environment_intensity, environment_rotation;
  std::string method;  // empty: the server's default, auto (pt or restir-gather, measured on the scene)
  uint32_t width = 256, height = 256, frames = 30, spp = 1, seed = 0, in_flight = 1;
  uint32_t max_depth = 0;  // 0: the server's default
  float exposure = 0.0f;
  std::string encodings = "exr,png";
  std::string out = "out/stream";
  std::string camera_path;
  double timeout_s = 600.0;
  bool keep_session = false;
  bool frames_given = false;
  RestirFlags restir;  // sent only when given, so that the server's defaults apply
};

double ms_since(Clock::time_point t) { return std::chrono::duration<double, std::milli>(Clock::now() - t).count(); }

v1::CreateSessionRequest make_request(const StreamArgs& a) {
  v1::CreateSessionRequest req;
  const int sources = int(!a.scene_file.empty()) + int(!a.scene_path.empty());
  if (sources > 1) throw std::runtime_error("give at most one of --scene-file and --scene-path (or --scene)");
  if (!a.scene_file.empty()) {
    std::ifstream in(a.scene_file, std::ios::binary);
    if (!in) throw std::runtime_error("cannot read --scene-file " + a.scene_file);
    req.mutable_scene()->set_glb(std::string(std::istreambuf_iterator<char>(in), {}));
    req.mutable_scene()->set_label(fs::path(a.scene_file).filename().string());
  } else if (!a.scene_path.empty()) {
    req.mutable_scene()->set_path(a.scene_path);
  } else {
    req.mutable_scene()->set_builtin(a.scene);
  }
  if (!a.environment_file.empty() && !a.environment_path.empty())
    throw std::runtime_error("give at most one of --environment-file and --environment-path");
  if (!a.environment_file.empty() || !a.environment_path.empty()) {
    v1::EnvironmentSource& env = *req.mutable_scene()->mutable_environment();
    if (!a.environment_file.empty()) {
      std::ifstream in(a.environment_file, std::ios::binary);
      if (!in) throw std::runtime_error("cannot read --environment-file " + a.environment_file);
      env.set_image(std::string(std::istreambuf_iterator<char>(in), {}));
      env.set_label(fs::path(a.environment_file).filename().string());
    } else {
      env.set_path(a.environment_path);
    }
    if (a.environment_intensity) env.set_intensity(*a.environment_intensity);
    if (a.environment_rotation) env.set_rotation_degrees(*a.environment_rotation);
  }
  req.mutable_resolution()->set_width(a.width);
  req.mutable_resolution()->set_height(a.height);
  req.set_method(a.method);
  req.set_seed(a.seed);
  req.mutable_options()->set_spp(a.spp);
  if (a.max_depth) req.mutable_options()->set_max_depth(a.max_depth);
  req.mutable_options()->set_exposure(a.exposure);
  set_restir_options(a.restir, *req.mutable_options());
  for (auto e : parse_encoding_list(a.encodings)) req.add_encodings(e);
  return req;
}

// One line of a frame's reuse statistics for the log: the counters, then the shift failures
// summed by pass ("temporal", "spatial"); empty when the frame has none (pt).
std::string reuse_line(const v1::FrameStatistics& st) {
  if (!st.has_reuse()) return "";
  const auto& r = st.reuse();
  std::map<std::string, uint64_t> counters, failures;  // ordered by name
  for (const auto& [key, n] : r.counters()) counters[key] = n;
  for (const auto& [key, n] : r.shift_failures()) failures[key.substr(0, key.find('.'))] += n;
  std::string line = "reuse";
  for (const auto& [key, n] : counters) line += " " + key + "=" + std::to_string(n);
  for (const auto& [pass, n] : failures) line += " " + pass + ".failures=" + std::to_string(n);
  return line;
}

// Adds a frame's reuse statistics to `totals` (counters and shift failures by key).
void add_reuse(const v1::FrameStatistics& st, nlohmann::json& totals) {
  if (!st.has_reuse()) return;
  auto add = [](nlohmann::json& into, const std::string& key, uint64_t n) {
    into[key] = (into.contains(key) ? into[key].get<uint64_t>() : 0) + n;
  };
  for (const auto& [key, n] : st.reuse().counters()) add(totals["counters"], key, n);
  for (const auto& [key, n] : st.reuse().shift_failures()) add(totals["shift_failures"], key, n);
}


int run_stream(const StreamArgs& a) {
  const auto script = a.camera_path.empty() ? std::vector<v1::FrameInput>{} : load_camera_path(a.camera_path);
  const uint32_t frames = !script.empty() && !a.frames_given ? uint32_t(script.size()) : a.frames;
  if (frames == 0) throw std::runtime_error("--frames must be at least 1");
  if (!script.empty() && frames > script.size())
    throw std::runtime_error("--frames = " + std::to_string(frames) + " but " + a.camera_path + " has " +
                             std::to_string(script.size()) + " frames");
  if (a.in_flight == 0) throw std::runtime_error("--in-flight must be at least 1");
  const auto timeout = std::chrono::milliseconds(int64_t(a.timeout_s * 1000.0));
  const v1::CreateSessionRequest request = make_request(a);

  // The server's limits first: the streaming channel takes frames up to limits.max_frame_bytes.
  // Every call carries x-strata-session, so a session-affine proxy sends all of them (the status
  // that sizes the channel included) to the daemon that will hold the session.
  v1::CreateSessionRequest create = request;
  create.set_session_id(a.session_id.empty() ? new_session_id() : a.session_id);
  const std::string& affinity = create.session_id();
  std::map<std::string, std::string> instances;  // call -> x-strata-instance that answered it
  auto stub = v1::RenderService::NewStub(open_channel(a.conn, affinity));
  v1::ServerStatus status;
  {
    grpc::ClientContext ctx;
    set_deadline(ctx, std::chrono::seconds(30));
    auto st = stub->GetServerStatus(&ctx, {}, &status);
    if (!st.ok()) throw RpcError("GetServerStatus (" + a.conn.server + ")", st);
    instances["GetServerStatus"] = instance_of(ctx);
  }
  stub = v1::RenderService::NewStub(
      open_channel(a.conn, affinity, status.limits().max_frame_bytes(), create.ByteSizeLong() + (1u << 20)));

  v1::Session session;
  {
    grpc::ClientContext ctx;
    set_deadline(ctx, timeout);
    auto st = stub->CreateSession(&ctx, create, &session);
    if (!st.ok()) throw RpcError("CreateSession", st);
    instances["CreateSession"] = instance_of(ctx);
  }
  fs::create_directories(a.out);
  std::cerr << "strata: " << session.name() << ": '" << session.scene() << "' " << a.width << "x" << a.height << " "
            << session.method() << " on " << status.device() << " (" << a.conn.server << ", instance "
            << instances["CreateSession"] << ")\n";

  nlohmann::json doc;
  doc["server"] = {{"address", a.conn.server}, {"device", status.device()}, {"instance", instances["CreateSession"]}};
  doc["session"] = message_to_json(session);
  doc["frames"] = nlohmann::json::array();

  grpc::ClientContext stream_ctx;
  set_deadline(stream_ctx, timeout);
  auto stream = stub->Stream(&stream_ctx);
  Progress progress(frames, Progress::stderr_is_terminal());
  std::map<uint64_t, Clock::time_point> sent_at;
  std::vector<double> latencies;
  uint64_t sent = 0, acked = 0, received = 0, dropped = 0, coalesced = 0;
  nlohmann::json reuse_totals = nlohmann::json::object();
  const auto start = Clock::now();
  bool stream_ok = true;
  while (acked < frames) {
    while (sent < frames && sent - acked < a.in_flight) {
      v1::FrameInput in = script.empty() ? v1::FrameInput() : script[sent];
      if (script.empty()) in.set_animation_frame(uint32_t(sent));
      if (sent == 0) in.set_session(session.name());
      in.set_sequence(sent + 1);
      sent_at[sent + 1] = Clock::now();
      if (!stream->Write(in)) break;
      ++sent;
    }
    v1::Frame frame;
    if (!stream->Read(&frame)) {
      stream_ok = false;
      break;
    }
    if (received == 0) instances["Stream"] = instance_of(stream_ctx);  // initial metadata came with the first frame
    const double latency = ms_since(sent_at.at(frame.input_sequence()));
    acked = frame.input_sequence();
    ++received;
    dropped += frame.frames_dropped();
    coalesced += frame.inputs_coalesced();
    latencies.push_back(latency);
    nlohmann::json j = write_frame(frame, a.out, a.exposure);  // statistics.reuse included when present
    j["client"] = {{"latency_ms", latency}, {"received_s", ms_since(start) / 1000.0}};
    doc["frames"].push_back(std::move(j));
    add_reuse(frame.statistics(), reuse_totals);
    progress.frame(acked, frame.frame_index(), latency, frame.gpu_ms_total(), frame.frames_dropped(),
                   reuse_line(frame.statistics()));
  }
  progress.finish();
  stream->WritesDone();
  const grpc::Status st = stream->Finish();
  if (!st.ok() || !stream_ok) {
    if (st.ok()) throw std::runtime_error("Stream: the server ended the stream after " + std::to_string(received) + " frames");
    throw RpcError("Stream", st);
  }
  const double wall = ms_since(start) / 1000.0;
  const util::Summary lat = util::summarize(latencies);
  doc["summary"] = {{"frames_received", received}, {"inputs_sent", sent}, {"frames_dropped", dropped},
                    {"inputs_coalesced", coalesced}, {"wall_s", wall}, {"fps", double(received) / wall},
                    {"latency_ms", {{"mean", lat.mean}, {"p50", lat.p50}, {"p95", lat.p95}, {"max", lat.max}}},
                    {"in_flight", a.in_flight}};
  if (!reuse_totals.empty()) doc["summary"]["reuse"] = std::move(reuse_totals);  // summed over the frames received
  if (!a.keep_session) {
    grpc::ClientContext ctx;
    set_deadline(ctx, std::chrono::seconds(30));
    v1::DeleteSessionRequest del;
    del.set_name(session.name());
    google::protobuf::Empty empty;
    auto dst = stub->DeleteSession(&ctx, del, &empty);
    if (!dst.ok()) throw RpcError("DeleteSession", dst);
    instances["DeleteSession"] = instance_of(ctx);
  }
  // Which daemon answered each call (behind a session-affine proxy: always the same one).
  doc["server"]["instances"] = instances;
  std::ofstream(fs::path(a.out) / "frames.json") << doc.dump(2) << "\n";
  std::cout << "wrote " << received << " frame(s) of '" << session.scene() << "' to " << a.out << " (" << double(received) / wall
            << " fps, latency mean " << lat.mean << " ms, p95 " << lat.p95 << " ms)\n";
  return 0;
}

}  // namespace

Runner add_stream_command(CLI::App& app) {
  auto a = std::make_shared<StreamArgs>();
  auto* cmd = app.add_subcommand("stream", "stream frames of a scene from stratad serve; write EXR, PNG and frames.json");
  add_connection_flags(cmd, a->conn);
  cmd->add_option("--session-id", a->session_id, "the session's id (sessions/{id}) and x-strata-session (default: a fresh random one)");
  cmd->add_option("--scene", a->scene, "built-in scene name")->capture_default_str();
  cmd->add_option("--scene-file", a->scene_file, "a local .glb file, sent inline");
  cmd->add_option("--scene-path", a->scene_path, "a .gltf/.glb file in the server's --scene-dir");
  cmd->add_option("--environment-file", a->environment_file, "a local equirectangular .hdr/.exr environment map, sent inline");
  cmd->add_option("--environment-path", a->environment_path, "an equirectangular .hdr/.exr environment map in the server's --scene-dir");
  cmd->add_option("--environment-intensity", a->environment_intensity, "scales the environment map's radiance (default 1)");
  cmd->add_option("--environment-rotation", a->environment_rotation,
                  "turns the environment map about +Y, degrees counter-clockwise seen from above (default 0)");
  cmd->add_option("--method", a->method,
                  "rendering method: one of the server's (ServerStatus.methods; stratad render --help describes each); "
                  "default: the server's default, auto: it measures pt and restir-gather on the scene's first frames and keeps "
                  "the one with the lower error at equal time (spp must then be 1; --method pt for more)");
  cmd->add_option("--width", a->width, "image width")->capture_default_str();
  cmd->add_option("--height", a->height, "image height")->capture_default_str();
  auto* frames = cmd->add_option("--frames", a->frames, "frames to stream (default: the camera path's length)")->capture_default_str();
  cmd->add_option("--spp", a->spp, "samples per pixel per frame")->capture_default_str();
  cmd->add_option("--max-depth", a->max_depth, "path segments (default: the server's)");
  cmd->add_option("--seed", a->seed, "random seed")->capture_default_str();
  cmd->add_option("--exposure", a->exposure, "PNG preview exposure in stops")->capture_default_str();
  cmd->add_option("--encodings", a->encodings, "images to request: exr, raw, png, domain (the domain map of restir-multilayer; comma-separated)")->capture_default_str();
  cmd->add_option("--out", a->out, "output directory")->capture_default_str();
  cmd->add_option("--camera-path", a->camera_path, "JSON script of FrameInputs, one per frame (see client/camera_path.h)");
  cmd->add_option("--in-flight", a->in_flight, "inputs sent ahead of the frames received (1: lockstep, reproducible)")
      ->capture_default_str();
  cmd->add_option("--timeout", a->timeout_s, "seconds for the whole stream")->capture_default_str();
  cmd->add_flag("--keep-session", a->keep_session, "do not delete the session at the end");
  // ReSTIR options (restir-* methods; pt accepts them and the session reports them as not applying).
  add_restir_flags(cmd, a->restir);
  return [a, frames] {
    a->frames_given = frames->count() > 0;
    return run_stream(*a);
  };
}

}  // namespace strata::client
