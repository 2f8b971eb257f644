#include "ops/timed_observers.h"

#include <chrono>

namespace strata::ops {

TimedObservers::TimedObservers(prometheus::Registry& r, std::vector<std::shared_ptr<service::FrameObserver>> observers)
    : observers_(std::move(observers)),
      seconds_(prometheus::BuildHistogram()
                   .Name("strata_frame_observer_seconds")
                   .Help("Time the metrics and dashboard observers take on the frame path, per frame")
                   .Register(r)
                   .Add({}, prometheus::Histogram::BucketBoundaries{1e-6, 1e-5, 5e-5, 1e-4, 5e-4, 1e-3, 5e-3, 1e-2})) {}

void TimedObservers::on_frame(const service::FrameEvent& event) {
  const auto start = std::chrono::steady_clock::now();
  for (const auto& o : observers_) o->on_frame(event);
  seconds_.Observe(std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count());
}

}  // namespace strata::ops
