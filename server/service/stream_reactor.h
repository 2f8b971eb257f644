#pragma once
// One Stream call. Inputs are checked as they arrive and merged into one pending input (latest
// input wins); the frame scheduler renders it; the frame waits in a one-frame slot (latest frame
// wins: a newer frame replaces it and the drop is counted) until the previous write completes, is
// encoded on the worker pool, and written. A stream thus holds at most one pending input, one frame
// in the slot and one frame being encoded or written, however slowly its client reads.
//
// gRPC calls (StartRead, StartWrite, Finish) are never made under mu_: their reactions may run
// inline. Decisions are taken under mu_ (next_locked) and carried out after (act).
#include <chrono>
#include <memory>
#include <mutex>
#include <optional>

#include <grpcpp/grpcpp.h>

#include "service/frame_input.h"
#include "service/frame_scheduler.h"
#include "service/service_core.h"
#include "service/session.h"
#include "strata/v1/render.grpc.pb.h"

namespace strata::service {

class StreamReactor final : public grpc::ServerBidiReactor<v1::FrameInput, v1::Frame>,
                            public AttachedStream,
                            public ScheduledStream,
                            public std::enable_shared_from_this<StreamReactor> {
 public:
  using Clock = std::chrono::steady_clock;

  // Serves a Stream call; the reactor keeps itself alive until gRPC is done with it (OnDone).
  static grpc::ServerBidiReactor<v1::FrameInput, v1::Frame>* start(ServiceCore& core, grpc::CallbackServerContext* ctx);
  StreamReactor(ServiceCore& core, grpc::CallbackServerContext* ctx);

  void end(grpc::Status status) override;
  void drain(grpc::Status status) override;
  void enforce_end_deadline(Clock::time_point now) override;
  void render_pending() override;

 private:
  void OnReadDone(bool ok) override;
  void OnWriteDone(bool ok) override;
  void OnCancel() override;
  void OnDone() override;

  struct Action {
    std::optional<grpc::Status> finish;
    std::shared_ptr<RenderedFrame> encode;
    bool enqueue = false;
  };
  void handle_input();  // in_ holds a new message; throws ServiceError
  std::shared_ptr<Session> attach_first(const v1::FrameInput& in);
  void request_finish_locked(grpc::Status status, bool immediate);
  bool ending_now_locked() const { return finished_ || (finish_status_ && finish_immediate_); }
  void put_in_slot_locked(RenderedFrame frame);
  Action next_locked();
  void act(Action a);
  void encode_and_write(std::shared_ptr<RenderedFrame> frame);

  ServiceCore& core_;
  std::shared_ptr<StreamReactor> self_;  // until OnDone
  v1::FrameInput in_;                    // owned by the read in flight
  v1::Frame out_;                        // owned by the write in flight
  GaugeHold out_held_;

  std::recursive_mutex ctx_mu_;          // guards the use of ctx_ against OnDone
  grpc::CallbackServerContext* ctx_;
  bool ctx_valid_ = true;

  std::mutex mu_;
  std::shared_ptr<Session> session_;
  uint64_t last_sequence_ = 0;
  std::optional<PendingInput> pending_;
  std::optional<RenderedFrame> slot_;
  uint64_t dropped_since_sent_ = 0;
  bool queued_ = false, rendering_ = false, writing_ = false;
  bool in_read_handler_ = false;         // Finish waits until the next read has been started
  bool accept_inputs_ = true;
  std::optional<grpc::Status> finish_status_;
  bool finish_immediate_ = false;
  bool finished_ = false;
  std::optional<Clock::time_point> end_deadline_;
  bool cancel_sent_ = false;
};

}  // namespace strata::service
