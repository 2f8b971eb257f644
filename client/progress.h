#pragma once
// Progress of a stream on stderr: a bar with frame rate and latency on a terminal, plain lines
// otherwise (logs, CI).
#include <chrono>
#include <cstdint>
#include <string>

namespace strata::client {

class Progress {
 public:
  Progress(uint64_t total, bool terminal);
  static bool stderr_is_terminal();
  // One received frame: inputs answered so far (`done` of the total), its index, the latency from
  // sending its input, its GPU time, frames dropped before it, and a detail line (reuse
  // statistics; shown in plain-line mode, empty for none).
  void frame(uint64_t done, uint64_t frame_index, double latency_ms, double gpu_ms, uint64_t dropped,
             const std::string& detail = "");
  void finish();

 private:
  uint64_t total_;
  bool terminal_;
  std::chrono::steady_clock::time_point start_;
  double latency_sum_ = 0.0;
  uint64_t count_ = 0;
};

}  // namespace strata::client
