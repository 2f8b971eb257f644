#pragma once
// The per-frame Prometheus metrics, fed by the sessions through FrameObserver: frames rendered,
// frame latency, GPU seconds by pass, history resets by reason, shift failures by pass and reason,
// rays, and the domain statistics as counters (so that a coverage ratio is a rate expression).
// Labels are bounded sets (method, pass, reason, layer); a session id never becomes a label.
#include <map>
#include <memory>
#include <mutex>
#include <string>

#include <prometheus/counter.h>
#include <prometheus/family.h>
#include <prometheus/histogram.h>
#include <prometheus/registry.h>

#include "service/frame_observer.h"

namespace strata::ops {

class FrameMetrics final : public service::FrameObserver {
 public:
  explicit FrameMetrics(prometheus::Registry& registry);
  void on_frame(const service::FrameEvent& event) override;

  // The bounded label value of a session's free-text history reset reason.
  static std::string reset_reason_label(const std::string& reason);

 private:
  prometheus::Family<prometheus::Counter>& frames_;
  prometheus::Family<prometheus::Histogram>& latency_;
  prometheus::Family<prometheus::Histogram>& render_;
  prometheus::Family<prometheus::Histogram>& pass_gpu_;
  prometheus::Family<prometheus::Histogram>& frame_gpu_;
  prometheus::Family<prometheus::Counter>& resets_;
  prometheus::Family<prometheus::Counter>& shift_failures_;
  prometheus::Family<prometheus::Counter>& rays_;
  prometheus::Family<prometheus::Counter>& domains_;
  prometheus::Counter& disoccluded_;
  prometheus::Counter& disoccluded_covered_;
};

}  // namespace strata::ops
