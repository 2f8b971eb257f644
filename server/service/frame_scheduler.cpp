#include "service/frame_scheduler.h"

#include <chrono>

namespace strata::service {

FrameScheduler::FrameScheduler() : thread_([this] { run(); }) {}

FrameScheduler::~FrameScheduler() { stop(); }

void FrameScheduler::stop() {
  {
    std::lock_guard lock(mu_);
    if (stop_ && !thread_.joinable()) return;
    stop_ = true;
  }
  cv_.notify_all();
  if (thread_.joinable() && thread_.get_id() != std::this_thread::get_id()) thread_.join();
}

void FrameScheduler::enqueue(std::shared_ptr<ScheduledStream> stream) {
  {
    std::lock_guard lock(mu_);
    if (stop_) return;
    queue_.push_back(std::move(stream));
  }
  cv_.notify_one();
}

bool FrameScheduler::wait_idle(std::chrono::milliseconds timeout) {
  std::unique_lock lock(mu_);
  return idle_cv_.wait_for(lock, timeout, [&] { return queue_.empty() && !rendering_; });
}

uint64_t FrameScheduler::rounds() const {
  std::lock_guard lock(mu_);
  return frames_;
}

void FrameScheduler::run() {
  std::unique_lock lock(mu_);
  for (;;) {
    cv_.wait(lock, [&] { return stop_ || !queue_.empty(); });
    if (stop_) break;
    auto stream = std::move(queue_.front());
    queue_.pop_front();
    rendering_ = true;
    lock.unlock();
    stream->render_pending();  // reports its own errors to its client
    stream.reset();
    lock.lock();
    rendering_ = false;
    ++frames_;
    if (queue_.empty()) idle_cv_.notify_all();
  }
  queue_.clear();
  rendering_ = false;
  idle_cv_.notify_all();
}

}  // namespace strata::service
