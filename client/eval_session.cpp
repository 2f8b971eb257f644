#include "eval_session.h"

#include <stdexcept>

#include "connection.h"
#include "eval_frames.h"
#include "eval_method.h"

namespace strata::client {

EvalSession::EvalSession(v1::RenderService::Stub& stub, const v1::SceneSource& scene, const std::string& scene_name,
                         const std::string& method, uint32_t spp, const EvalSettings& s, std::chrono::milliseconds timeout)
    : stub_(stub), s_(s), what_(scene_name + ", " + method) {
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
  ++received_;
  return m;
}

void EvalSession::finish() {
  if (finished_) return;
  finished_ = true;
  stream_->WritesDone();
  const grpc::Status st = stream_->Finish();
  const grpc::Status deleted = delete_session();
  if (!st.ok()) throw RpcError("Stream (" + what_ + ")", st);
  if (!deleted.ok()) throw RpcError("DeleteSession", deleted);
}

}  // namespace strata::client
