#include "service/stream_reactor.h"

#include "service/errors.h"
#include "service/frame_message.h"

namespace strata::service {
namespace {

grpc::Status draining_status() {
  return {grpc::StatusCode::UNAVAILABLE, "stratad is draining (shutting down): no new streams; reconnect to another server"};
}

}  // namespace

grpc::ServerBidiReactor<v1::FrameInput, v1::Frame>* StreamReactor::start(ServiceCore& core, grpc::CallbackServerContext* ctx) {
  auto r = std::make_shared<StreamReactor>(core, ctx);
  r->self_ = r;
  core.metrics.streams.fetch_add(1);
  core.streams.add(r);
  if (core.draining.load()) {
    {
      std::lock_guard lock(r->mu_);
      r->finished_ = true;
    }
    r->Finish(draining_status());
  } else {
    r->StartRead(&r->in_);
  }
  return r.get();
}

StreamReactor::StreamReactor(ServiceCore& core, grpc::CallbackServerContext* ctx) : core_(core), ctx_(ctx) {}

// ---- decisions -------------------------------------------------------------------------------

void StreamReactor::request_finish_locked(grpc::Status status, bool immediate) {
  if (finished_) return;
  if (!finish_status_ || (immediate && !finish_immediate_)) {
    // An immediate end (error, deletion, cancellation) overrides a graceful one.
    if (!finish_status_ || finish_status_->ok() || immediate) finish_status_ = std::move(status);
    finish_immediate_ = finish_immediate_ || immediate;
  }
}

void StreamReactor::put_in_slot_locked(RenderedFrame frame) {
  if (slot_) {
    // Latest frame wins: the older one is dropped; what the client must still learn carries over.
    ++dropped_since_sent_;
    if (session_) session_->note_dropped(1);
    core_.metrics.frames_dropped.fetch_add(1);
    frame.coalesced += slot_->coalesced;
    if (slot_->history_reset) {
      frame.history_reset_reason = slot_->history_reset_reason + (frame.history_reset ? "; " + frame.history_reset_reason : "");
      frame.history_reset = true;
    }
    frame.option_changes.insert(frame.option_changes.begin(), slot_->option_changes.begin(), slot_->option_changes.end());
  }
  slot_ = std::move(frame);
}

StreamReactor::Action StreamReactor::next_locked() {
  Action a;
  if (finished_) return a;
  if (!writing_ && slot_ && !ending_now_locked()) {
    writing_ = true;
    slot_->dropped_before = dropped_since_sent_;
    dropped_since_sent_ = 0;
    a.encode = std::make_shared<RenderedFrame>(std::move(*slot_));
    slot_.reset();
  }
  if (finish_status_ && !writing_ && !in_read_handler_) {
    const bool nothing_left = !pending_ && !rendering_ && !slot_;
    if (finish_immediate_ || nothing_left) {
      finished_ = true;
      a.finish = *finish_status_;
      slot_.reset();
      pending_.reset();
      return a;
    }
  }
  if (pending_ && !queued_ && !rendering_ && !ending_now_locked()) {
    queued_ = true;
    a.enqueue = true;
  }
  return a;
}

void StreamReactor::act(Action a) {
  if (a.enqueue) core_.scheduler.enqueue(shared_from_this());
  if (a.encode) {
    auto self = shared_from_this();
    core_.pool.post([self, frame = std::move(a.encode)]() mutable { self->encode_and_write(std::move(frame)); });
  }
  if (a.finish) Finish(*a.finish);
}

// ---- reading ---------------------------------------------------------------------------------

std::shared_ptr<Session> StreamReactor::attach_first(const v1::FrameInput& in) {
  if (core_.draining.load()) throw ServiceError(draining_status().error_code(), draining_status().error_message());
  if (in.session().empty()) fail_invalid("session is required in the first FrameInput of a stream (sessions/{session})");
  auto s = core_.registry.get(in.session(), "session");
  if (!s->attach(shared_from_this()))
    fail(grpc::StatusCode::ABORTED, "session '" + s->name() + "' already has a stream attached; one stream per session at a time");
  try {
    core_.registry.get(s->name(), "session");  // deleted or expired while attaching
  } catch (...) {
    s->detach(this);
    throw;
  }
  std::lock_guard lock(mu_);
  session_ = s;
  return s;
}

void StreamReactor::handle_input() {
  const v1::FrameInput& in = in_;
  std::shared_ptr<Session> s;
  uint64_t last = 0;
  {
    std::lock_guard lock(mu_);
    s = session_;
    last = last_sequence_;
  }
  if (!s) {
    s = attach_first(in);
  } else if (!in.session().empty() && in.session() != s->name()) {
    fail_invalid("session = '" + in.session() + "' differs from this stream's session '" + s->name() +
                 "'; leave it empty after the first FrameInput");
  }
  if (in.sequence() <= last)
    fail_invalid(last == 0 ? "sequence = 0: sequences start at 1"
                           : "sequence = " + std::to_string(in.sequence()) + " is not greater than the previous sequence " +
                                 std::to_string(last));
  PendingInput input = parse_frame_input(in, s->scene(), core_.config.limits);
  check_method_options(s->checked_method(), input.options, "options", s->auto_method());
  check_method_encodings(s->method(), input.encodings, "encodings");
  s->note_input(in.sequence());
  std::lock_guard lock(mu_);
  last_sequence_ = in.sequence();
  if (!accept_inputs_) return;  // draining: only inputs that arrived before are rendered
  if (pending_) pending_->merge_newer(std::move(input));
  else pending_ = std::move(input);
}

void StreamReactor::OnReadDone(bool ok) {
  Action a;
  if (!ok) {  // the client half-closed (or the call ended): finish once its last input is sent
    std::lock_guard lock(mu_);
    accept_inputs_ = false;
    request_finish_locked(grpc::Status::OK, false);
    a = next_locked();
  } else {
    {
      std::lock_guard lock(mu_);
      in_read_handler_ = true;
    }
    const grpc::Status st = guarded([&] { handle_input(); });
    bool read_again = false;
    {
      std::lock_guard lock(mu_);
      if (!st.ok()) request_finish_locked(st, true);
      read_again = !finished_ && !finish_immediate_;
      if (!read_again) in_read_handler_ = false;
    }
    if (read_again) {
      StartRead(&in_);
      std::lock_guard lock(mu_);
      in_read_handler_ = false;
    }
    std::lock_guard lock(mu_);
    a = next_locked();
  }
  act(std::move(a));
}

// ---- rendering and writing -------------------------------------------------------------------

void StreamReactor::render_pending() {
  std::optional<PendingInput> input;
  std::shared_ptr<Session> s;
  {
    std::lock_guard lock(mu_);
    queued_ = false;
    if (!pending_ || ending_now_locked()) return;
    input = std::move(pending_);
    pending_.reset();
    rendering_ = true;
    s = session_;
  }
  std::optional<RenderedFrame> frame;
  grpc::Status error;
  try {
    frame = s->render(std::move(*input));
  } catch (const std::exception& e) {
    error = status_from_exception(e);
  }
  Action a;
  {
    std::lock_guard lock(mu_);
    rendering_ = false;
    if (!frame) request_finish_locked(error, true);
    else if (!ending_now_locked()) put_in_slot_locked(std::move(*frame));
    a = next_locked();
  }
  act(std::move(a));
}

void StreamReactor::encode_and_write(std::shared_ptr<RenderedFrame> frame) {
  v1::Frame message;
  const grpc::Status st = guarded([&] { message = make_frame_message(*frame); });
  frame.reset();  // the float image is no longer needed
  GaugeHold held(core_.metrics.buffered_frame_bytes, int64_t(message.ByteSizeLong()));
  bool start = false;
  Action a;
  {
    std::lock_guard lock(mu_);
    if (st.ok() && !ending_now_locked()) {
      out_ = std::move(message);
      out_held_ = std::move(held);
      start = true;
    } else {
      writing_ = false;
      if (!st.ok()) request_finish_locked(st, true);
      a = next_locked();
    }
  }
  if (start) StartWrite(&out_);  // Finish waits for OnWriteDone
  else act(std::move(a));
}

void StreamReactor::OnWriteDone(bool ok) {
  Action a;
  {
    std::lock_guard lock(mu_);
    writing_ = false;
    out_.Clear();
    out_held_.release();
    if (!ok) request_finish_locked(grpc::Status(grpc::StatusCode::CANCELLED, "the stream was cancelled"), true);
    a = next_locked();
  }
  act(std::move(a));
}

// ---- ending ----------------------------------------------------------------------------------

void StreamReactor::OnCancel() {
  Action a;
  {
    std::lock_guard lock(mu_);
    request_finish_locked(grpc::Status(grpc::StatusCode::CANCELLED, "the stream was cancelled"), true);
    a = next_locked();
  }
  act(std::move(a));
}

void StreamReactor::end(grpc::Status status) {
  Action a;
  {
    std::lock_guard lock(mu_);
    request_finish_locked(std::move(status), true);
    if (!end_deadline_) end_deadline_ = Clock::now() + core_.config.end_grace;
    a = next_locked();
  }
  act(std::move(a));
}

void StreamReactor::drain(grpc::Status status) {
  Action a;
  {
    std::lock_guard lock(mu_);
    accept_inputs_ = false;
    request_finish_locked(std::move(status), false);
    if (!end_deadline_) end_deadline_ = Clock::now() + core_.config.drain_timeout;
    a = next_locked();
  }
  act(std::move(a));
}

void StreamReactor::enforce_end_deadline(Clock::time_point now) {
  {
    std::lock_guard lock(mu_);
    if (finished_ || cancel_sent_ || !end_deadline_ || now < *end_deadline_) return;
    cancel_sent_ = true;
  }
  std::lock_guard ctx_lock(ctx_mu_);
  if (ctx_valid_) ctx_->TryCancel();  // the write in flight fails, then the stream finishes
}

void StreamReactor::OnDone() {
  {
    std::lock_guard ctx_lock(ctx_mu_);
    ctx_valid_ = false;
  }
  std::shared_ptr<Session> s;
  {
    std::lock_guard lock(mu_);
    finished_ = true;
    s = std::move(session_);
    pending_.reset();
    slot_.reset();
  }
  core_.metrics.streams.fetch_sub(1);
  if (s && s->detach(this)) core_.pool.post([s] { s->release_gpu(); });
  self_.reset();  // may destroy this reactor: nothing after this line
}

}  // namespace strata::service
