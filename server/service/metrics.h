#pragma once
// Server-wide counters (ServerStatus) and a gauge of the frame bytes the streams hold.
#include <atomic>
#include <cstdint>
#include <utility>

#include "service/frame_observer.h"

namespace strata::service {

struct ServiceMetrics {
  std::atomic<uint64_t> sessions_created{0};
  std::atomic<uint64_t> sessions_expired{0};
  std::atomic<uint64_t> frames_rendered{0};
  std::atomic<uint64_t> frames_dropped{0};
  std::atomic<uint64_t> inputs_coalesced{0};
  std::atomic<int64_t> buffered_frame_bytes{0};  // rendered frames in slots, being encoded or written
  std::atomic<uint32_t> streams{0};
  FrameObservers frame_observers;  // told of every rendered frame (metrics exporter, dashboard)
};

// Holds `bytes` on a gauge for as long as it lives (moves carry the bytes along).
class GaugeHold {
 public:
  GaugeHold() = default;
  GaugeHold(std::atomic<int64_t>& gauge, int64_t bytes) : gauge_(&gauge), bytes_(bytes) { gauge.fetch_add(bytes); }
  GaugeHold(GaugeHold&& o) noexcept : gauge_(std::exchange(o.gauge_, nullptr)), bytes_(std::exchange(o.bytes_, 0)) {}
  GaugeHold& operator=(GaugeHold&& o) noexcept {
    if (this != &o) {
      release();
      gauge_ = std::exchange(o.gauge_, nullptr);
      bytes_ = std::exchange(o.bytes_, 0);
    }
    return *this;
  }
  GaugeHold(const GaugeHold&) = delete;
  GaugeHold& operator=(const GaugeHold&) = delete;
  ~GaugeHold() { release(); }
  void release() {
    if (gauge_) gauge_->fetch_sub(bytes_);
    gauge_ = nullptr;
    bytes_ = 0;
  }

 private:
  std::atomic<int64_t>* gauge_ = nullptr;
  int64_t bytes_ = 0;
};

}  // namespace strata::service
