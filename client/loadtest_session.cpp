#include "loadtest_session.h"

#include <condition_variable>
#include <mutex>
#include <thread>

namespace strata::client {
namespace {

double ms_between(LoadClock::time_point a, LoadClock::time_point b) { return std::chrono::duration<double, std::milli>(b - a).count(); }

std::chrono::system_clock::time_point deadline_in(double seconds) {
  return std::chrono::system_clock::now() +
         std::chrono::duration_cast<std::chrono::system_clock::duration>(std::chrono::duration<double>(seconds));
}

// Shared by the sending thread and the reading thread of one stream.
struct StreamState {
  std::mutex mu;
  std::condition_variable cv;
  std::vector<InputRecord> inputs;
  std::vector<FrameRecord> frames;
  uint64_t answered = 0;  // inputs 1..answered have an answer
  bool reading_done = false;
};

}  // namespace

SessionResult run_session(const LoadtestOptions& o, const v1::CreateSessionRequest& request,
                          const std::vector<v1::FrameInput>& script, const std::shared_ptr<grpc::Channel>& channel,
                          Pacer& pacer, LoadProgress& progress, uint32_t index) {
  SessionResult result;
  result.index = index;
  auto stub = v1::RenderService::NewStub(channel);
  const auto timeout = std::chrono::duration_cast<LoadClock::duration>(std::chrono::duration<double>(o.timeout_s));

  {
    grpc::ClientContext ctx;
    ctx.set_deadline(deadline_in(o.timeout_s));
    v1::Session session;
    const auto t0 = LoadClock::now();
    const grpc::Status st = stub->CreateSession(&ctx, request, &session);
    result.rpcs.push_back({"CreateSession", st.error_code(), st.error_message(), ms_between(t0, LoadClock::now())});
    if (!st.ok()) return result;
    result.name = session.name();
  }

  // The stream's own deadline is a backstop; the waits below end it sooner (TryCancel).
  grpc::ClientContext stream_ctx;
  const double backstop_s = (o.duration_s > 0.0 ? o.duration_s : 0.0) + o.timeout_s +
                            (o.total > 0 && o.duration_s <= 0.0 ? double(o.total) * o.timeout_s : 0.0);
  stream_ctx.set_deadline(deadline_in(std::min(backstop_s, LoadtestOptions::k_max_duration_s + o.timeout_s)));
  const auto stream_t0 = LoadClock::now();
  result.stream_start = stream_t0;
  auto stream = stub->Stream(&stream_ctx);
  StreamState state;

  std::thread reader([&] {
    v1::Frame frame;
    while (stream->Read(&frame)) {
      const auto now = LoadClock::now();
      std::lock_guard lock(state.mu);
      const uint64_t seq = frame.input_sequence();
      state.frames.push_back({seq, now, frame.gpu_ms_total(), frame.timing().queued_ms(), frame.timing().render_ms(),
                              frame.frames_dropped(), frame.inputs_coalesced(), frame.history_reset()});
      uint64_t newly = 0;
      for (uint64_t s = state.answered + 1; s <= seq && s <= state.inputs.size(); ++s) {
        state.inputs[s - 1].answered = now;
        state.inputs[s - 1].own_frame = s == seq;
        ++newly;
      }
      state.answered = std::max(state.answered, std::min<uint64_t>(seq, state.inputs.size()));
      progress.received.fetch_add(1);
      progress.answered.fetch_add(newly);
      state.cv.notify_all();
    }
    std::lock_guard lock(state.mu);
    state.reading_done = true;
    state.cv.notify_all();
  });

  // Waits until every input sent has its answer, or the oldest unanswered one has waited
  // --timeout (then the stream is cancelled); false when the stream is over or was cancelled.
  auto wait_answered = [&](std::unique_lock<std::mutex>& lock) {
    while (state.answered < state.inputs.size() && !state.reading_done) {
      const auto oldest = state.inputs[state.answered].scheduled;
      if (state.cv.wait_until(lock, std::max(oldest, state.inputs[state.answered].sent) + timeout) == std::cv_status::timeout &&
          state.answered < state.inputs.size() && LoadClock::now() >= state.inputs[state.answered].sent + timeout) {
        result.timed_out = true;
        return false;
      }
    }
    return !state.reading_done;
  };

  bool ok = true;
  for (uint64_t k = 0; ok; ++k) {
    if (!o.open_loop()) {  // closed loop: the next input once the previous frame came back
      std::unique_lock lock(state.mu);
      if (!wait_answered(lock)) break;
    }
    const auto scheduled = pacer.next();
    if (!scheduled) break;
    if (o.open_loop()) {
      // Sleep until the scheduled time, watching for an answer that is overdue meanwhile.
      std::unique_lock lock(state.mu);
      while (LoadClock::now() < *scheduled && !state.reading_done) {
        if (state.answered < state.inputs.size() && LoadClock::now() >= state.inputs[state.answered].sent + timeout) {
          result.timed_out = true;
          break;
        }
        state.cv.wait_until(lock, std::min(*scheduled, LoadClock::now() + std::chrono::milliseconds(50)));
      }
      if (result.timed_out || state.reading_done) break;
    }
    v1::FrameInput in = script.empty() ? v1::FrameInput() : script[k % script.size()];
    if (script.empty()) in.set_animation_frame(uint32_t(k));
    if (k == 0) in.set_session(result.name);
    in.set_sequence(k + 1);
    {
      std::lock_guard lock(state.mu);
      state.inputs.push_back({*scheduled, LoadClock::now(), std::nullopt, false});
    }
    ok = stream->Write(in);
    progress.sent.fetch_add(1);
  }
  if (!result.timed_out) {  // the last answers
    std::unique_lock lock(state.mu);
    wait_answered(lock);
  }
  if (result.timed_out) stream_ctx.TryCancel();
  stream->WritesDone();
  reader.join();
  const grpc::Status st = stream->Finish();
  result.rpcs.push_back({"Stream", st.error_code(), st.error_message(), ms_between(stream_t0, LoadClock::now())});
  result.stream_code = result.timed_out ? grpc::StatusCode::DEADLINE_EXCEEDED : st.error_code();
  result.stream_error = result.timed_out ? "no frame within --timeout = " + std::to_string(o.timeout_s) + " s"
                                         : st.error_message();
  result.inputs = std::move(state.inputs);
  result.frames = std::move(state.frames);
  for (const auto& in : result.inputs)
    if (!in.answered) progress.errors.fetch_add(1);

  {
    grpc::ClientContext ctx;
    ctx.set_deadline(deadline_in(o.timeout_s));
    v1::DeleteSessionRequest del;
    del.set_name(result.name);
    google::protobuf::Empty empty;
    const auto t0 = LoadClock::now();
    const grpc::Status dst = stub->DeleteSession(&ctx, del, &empty);
    result.rpcs.push_back({"DeleteSession", dst.error_code(), dst.error_message(), ms_between(t0, LoadClock::now())});
  }
  return result;
}

}  // namespace strata::client
