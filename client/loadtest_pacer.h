#pragma once
// Hands out frame requests to the sessions: each gets a scheduled send time. With a rate (--rps or
// a step/line schedule) the times follow the schedule whatever the server does, so a frame's
// latency is measured from when it should have been sent (no coordinated omission: a slow server
// cannot hide the queue it causes by slowing the sender down). Without one, a request is
// scheduled when a session asks for it (closed loop: each session sends its next input once the
// previous frame came back). The pacer stops at -n requests or -z seconds, whichever comes first.
#include <chrono>
#include <cstdint>
#include <mutex>
#include <optional>

#include "loadtest_options.h"

namespace strata::client {

class Pacer {
 public:
  using Clock = std::chrono::steady_clock;
  Pacer(const LoadtestOptions& options, Clock::time_point start);
  // The next request's scheduled time; nullopt once the run is over.
  std::optional<Clock::time_point> next();
  uint64_t issued() const;
  Clock::time_point start() const { return start_; }
  // When the run ends at the latest (the -z duration), or nullopt for a count-only run.
  std::optional<Clock::time_point> end() const { return end_; }

 private:
  const LoadtestOptions& options_;
  const Clock::time_point start_;
  std::optional<Clock::time_point> end_;
  mutable std::mutex mu_;
  uint64_t issued_ = 0;
  double next_s_ = 0.0;  // open loop: the next scheduled time, seconds after start
};

}  // namespace strata::client
