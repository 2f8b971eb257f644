#pragma once
// Runs the ops observers (metrics, dashboard) of each frame and measures what they cost the frame
// path: strata_frame_observer_seconds, next to strata_frame_render_seconds, gives the overhead of
// metrics and dashboard on frame time as a ratio of two sums, in one run.
#include <memory>
#include <vector>

#include <prometheus/family.h>
#include <prometheus/histogram.h>
#include <prometheus/registry.h>

#include "service/frame_observer.h"

namespace strata::ops {

class TimedObservers final : public service::FrameObserver {
 public:
  TimedObservers(prometheus::Registry& registry, std::vector<std::shared_ptr<service::FrameObserver>> observers);
  void on_frame(const service::FrameEvent& event) override;

 private:
  std::vector<std::shared_ptr<service::FrameObserver>> observers_;
  prometheus::Histogram& seconds_;
};

}  // namespace strata::ops
