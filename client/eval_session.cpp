#include "eval_session.h"

#include <stdexcept>
#include <thread>

#include "connection.h"
#include "eval_frames.h"
#include "eval_method.h"

namespace strata::client {

namespace {

// A frame of the daemon's progressive start: rendered by the stand-in (pt) while the session's own
// method compiles (docs/ARCHITECTURE.md, "First frames"). Its passes are pt's.
bool from_stand_in(const v1::Frame& frame, const std::string& method) {
  if (method == "pt" || method == "auto") return false;
  for (const auto& p : frame.pass_ms())
    if (p.pass() == "path_trace") return true;
  return false;
}

}  // namespace

EvalSession::EvalSession(v1::RenderService::Stub& stub, const v1::SceneSource& scene, const std::string& scene_name,
                         const std::string& method, uint32_t spp, const EvalSettings& s, std::chrono::milliseconds timeout)
    : stub_(stub), s_(s), what_(scene_name + ", " + method) {
  method_ = parse_eval_method(method, s.restir).method;
  v1::CreateSessionRequest req;
  *req.mutable_scene() = scene;
  req.mutable_resolution()->set_width(s.width);
  req.mutable_resolution()->set_height(s.height);
  const EvalMethod m = parse_eval_method(method, s.restir);  // NAME[:FLAG=VALUE]... (eval_method.h)
  req.set_method(m.method);
  req.set_seed(s.seed);
  req.mutable_options()->set_spp(spp);
  if (s.max_depth) req.mutable_options()->set_max_depth(s.max_depth);
  if (s.splats_per_frame) req.mutable_options()->set_splats_per_frame(*s.splats_per_frame);
  set_restir_options(m.restir, *req.mutable_options());
  req.add_encodings(v1::IMAGE_ENCODING_RAW_RGBA16F);
  {
    grpc::ClientContext ctx;
    set_deadline(ctx, timeout);
    auto st = stub_.CreateSession(&ctx, req, &session_);
    if (!st.ok()) throw RpcError("CreateSession (" + what_ + ", spp " + std::to_string(spp) + ")", st);
  }
  set_deadline(ctx_, timeout);
  stream_ = stub_.Stream(&ctx_);
}

EvalSession::~EvalSession() {
  if (finished_) return;
  ctx_.TryCancel();  // ends the call before the stream goes
  (void)stream_->Finish();
  (void)delete_session();
}

grpc::Status EvalSession::delete_session() {
  grpc::ClientContext ctx;
  set_deadline(ctx, std::chrono::seconds(30));
  v1::DeleteSessionRequest del;
  del.set_name(session_.name());
  google::protobuf::Empty empty;
  return stub_.DeleteSession(&ctx, del, &empty);
}

MethodImage EvalSession::next(uint32_t f) {
  v1::FrameInput in = eval_frame_input(s_, f);
  if (received_ == 0) in.set_session(session_.name());
  in.set_sequence(f + 1);
  v1::Frame frame;
  if (!stream_->Write(in) || !stream_->Read(&frame)) {
    finish();  // the stream's status says why
    throw std::runtime_error("Stream (" + what_ + "): the server ended the stream after " + std::to_string(received_) +
                             " of " + std::to_string(s_.frames) + " frames");
  }
  if (frame.input_sequence() != f + 1 || frame.images_size() == 0)
    throw std::runtime_error("Stream: frame " + std::to_string(frame.frame_index()) + " answers input " +
                             std::to_string(frame.input_sequence()) + ", expected " + std::to_string(f + 1));
  MethodImage m;
  m.frame = f;
  m.image = decode_image(frame.images(0));
  m.gpu_ms = frame.gpu_ms_total();
  for (const auto& p : frame.pass_ms()) m.pass_ms[p.pass()] += p.ms();
  for (const auto& d : frame.option_changes())
    if (d.name() == "method") {
      m.chosen_method = d.value();
      m.choice_reason = d.reason();
    }
  ++received_;
  if (from_stand_in(frame, method_)) stand_in_frames_++;
  return m;
}

bool EvalSession::compiling() {
  grpc::ClientContext ctx;
  set_deadline(ctx, std::chrono::seconds(30));
  v1::GetSessionRequest req;
  req.set_name(session_.name());
  v1::Session s;
  const grpc::Status st = stub_.GetSession(&ctx, req, &s);
  if (!st.ok()) throw RpcError("GetSession (" + what_ + ")", st);
  // The progressive start says so in its frames' pass decisions: "METHOD compiling: rendered by pt"
  // (the stand-in), or a history pass "held: its pipelines are compiling in the background".
  for (const auto& p : s.passes())
    if (p.reason().find("compiling") != std::string::npos) return true;
  return false;
}

void wait_until_compiled(v1::RenderService::Stub& stub, const v1::SceneSource& scene, const std::string& scene_name,
                         const std::string& method, const EvalSettings& s, std::chrono::milliseconds timeout) {
  const std::string name = parse_eval_method(method, s.restir).method;
  if (name == "pt" || name == "auto") return;
  const auto deadline = std::chrono::steady_clock::now() + timeout;
  EvalSettings two = s;
  two.frames = 2;  // the second frame has a previous one: its history passes run unless held
  for (;;) {
    EvalSession session(stub, scene, scene_name, method, 1, two, timeout);
    session.probe_ = true;
    session.next(0);
    session.next(1);
    const bool compiled = session.stand_in_frames() == 0 && !session.compiling();
    session.finish();
    if (compiled) return;
    if (std::chrono::steady_clock::now() > deadline)
      throw std::runtime_error("strata eval (" + scene_name + ", " + method + "): the daemon still renders its stand-in while " + name +
                               " compiles; try again later");
    std::this_thread::sleep_for(std::chrono::seconds(2));
  }
}

void EvalSession::finish() {
  if (finished_) return;
  finished_ = true;
  stream_->WritesDone();
  const grpc::Status st = stream_->Finish();
  const grpc::Status deleted = delete_session();
  if (!st.ok()) throw RpcError("Stream (" + what_ + ")", st);
  if (!deleted.ok()) throw RpcError("DeleteSession", deleted);
  if (!probe_ && stand_in_frames_ > 0)
    throw std::runtime_error("Stream (" + what_ + "): " + std::to_string(stand_in_frames_) + " of " + std::to_string(received_) +
                             " frames came from the daemon's stand-in (pt) while " + method_ +
                             " compiled: they would be scored as " + method_);
}

}  // namespace strata::client
