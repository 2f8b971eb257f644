#pragma once
// One session of a load test: CreateSession, one Stream paced by the Pacer, DeleteSession, each
// call's status and time recorded. A frame answers its own input and every earlier one not yet
// answered (inputs merged on the server, or whose frames were dropped), so every input's latency
// is measured from its scheduled send time to the frame that answered it.
#include <atomic>
#include <chrono>
#include <cstdint>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include <grpcpp/grpcpp.h>

#include "loadtest_options.h"
#include "loadtest_pacer.h"
#include "strata/v1/render.grpc.pb.h"

namespace strata::client {

using LoadClock = std::chrono::steady_clock;

struct InputRecord {
  LoadClock::time_point scheduled, sent;
  std::optional<LoadClock::time_point> answered;
  bool own_frame = false;  // answered by the frame rendered for it (else merged or dropped)
};

struct FrameRecord {
  uint64_t input_sequence = 0;
  LoadClock::time_point received;
  double gpu_ms = 0.0, queued_ms = 0.0, render_ms = 0.0;
  uint64_t dropped = 0, coalesced = 0;
  bool history_reset = false;
};

struct RpcRecord {
  std::string method;
  grpc::StatusCode code = grpc::StatusCode::OK;
  std::string message;
  double ms = 0.0;
};

struct SessionResult {
  uint32_t index = 0;
  std::string name;                      // sessions/{id}; empty when CreateSession failed
  std::vector<InputRecord> inputs;       // by sequence - 1
  std::vector<FrameRecord> frames;
  std::vector<RpcRecord> rpcs;           // CreateSession, Stream, DeleteSession
  std::optional<LoadClock::time_point> stream_start;
  grpc::StatusCode stream_code = grpc::StatusCode::OK;  // unanswered inputs are counted with it
  std::string stream_error;
  bool timed_out = false;                // a frame did not come within --timeout
};

// Counters the progress display reads while the sessions run.
struct LoadProgress {
  std::atomic<uint64_t> sent{0}, answered{0}, received{0}, errors{0};
};

// Runs one session to the end (bounded: the pacer's count or duration, and --timeout per wait).
SessionResult run_session(const LoadtestOptions& options, const v1::CreateSessionRequest& request,
                          const std::vector<v1::FrameInput>& script, const std::shared_ptr<grpc::Channel>& channel,
                          Pacer& pacer, LoadProgress& progress, uint32_t index);

}  // namespace strata::client
