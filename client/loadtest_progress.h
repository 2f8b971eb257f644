#pragma once
// The load test's progress while it runs: a bar on a terminal (stderr), a line every few seconds
// otherwise; polled from its own thread so that the sessions never wait for the display.
#include <atomic>
#include <chrono>
#include <thread>

#include "loadtest_options.h"
#include "loadtest_session.h"

namespace strata::client {

class LoadtestProgress {
 public:
  LoadtestProgress(const LoadtestOptions& options, const LoadProgress& counters, LoadClock::time_point start);
  ~LoadtestProgress();  // stops the display thread and ends the bar's line
  LoadtestProgress(const LoadtestProgress&) = delete;
  LoadtestProgress& operator=(const LoadtestProgress&) = delete;

 private:
  void show(bool last);
  const LoadtestOptions& options_;
  const LoadProgress& counters_;
  const LoadClock::time_point start_;
  const bool terminal_;
  std::atomic<bool> stop_{false};
  std::thread thread_;
};

}  // namespace strata::client
