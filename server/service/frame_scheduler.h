#pragma once
// One device shared fairly: streams with pending input wait in one FIFO; the scheduler thread
// renders one frame for the stream at the front, and a stream whose next input arrived meanwhile
// goes to the back. Every waiting stream gets a frame per round, however slow the others are.
#include <condition_variable>
#include <cstdint>
#include <deque>
#include <memory>
#include <mutex>
#include <thread>

namespace strata::service {

class ScheduledStream {
 public:
  virtual ~ScheduledStream() = default;
  // Renders the pending input, if any, and hands the frame on. A stream whose next input is
  // already pending enqueues itself again (it goes to the back).
  virtual void render_pending() = 0;
};

class FrameScheduler {
 public:
  FrameScheduler();
  ~FrameScheduler();  // stops after the frame in progress
  FrameScheduler(const FrameScheduler&) = delete;
  FrameScheduler& operator=(const FrameScheduler&) = delete;

  // The stream makes sure it is queued at most once at a time.
  void enqueue(std::shared_ptr<ScheduledStream> stream);
  // Waits until the queue is empty and no frame is rendering, or `timeout` passes; true when idle.
  bool wait_idle(std::chrono::milliseconds timeout);
  void stop();
  uint64_t rounds() const;

 private:
  void run();
  mutable std::mutex mu_;
  std::condition_variable cv_, idle_cv_;
  std::deque<std::shared_ptr<ScheduledStream>> queue_;
  bool rendering_ = false;
  bool stop_ = false;
  uint64_t frames_ = 0;
  std::thread thread_;
};

}  // namespace strata::service
