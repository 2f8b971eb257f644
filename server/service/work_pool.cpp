#include "service/work_pool.h"

#include <cstdio>
#include <exception>

namespace strata::service {

WorkPool::WorkPool(uint32_t threads) {
  for (uint32_t i = 0; i < threads; ++i) threads_.emplace_back([this] { run(); });
}

WorkPool::~WorkPool() {
  {
    std::lock_guard lock(mu_);
    stop_ = true;
  }
  cv_.notify_all();
  for (auto& t : threads_) t.join();
}

void WorkPool::post(std::function<void()> job) {
  {
    std::lock_guard lock(mu_);
    jobs_.push_back(std::move(job));
  }
  cv_.notify_one();
}

void WorkPool::wait_idle() {
  std::unique_lock lock(mu_);
  idle_cv_.wait(lock, [&] { return jobs_.empty() && busy_ == 0; });
}

void WorkPool::run() {
  std::unique_lock lock(mu_);
  for (;;) {
    cv_.wait(lock, [&] { return stop_ || !jobs_.empty(); });
    if (jobs_.empty()) return;  // stopping, and nothing left
    auto job = std::move(jobs_.front());
    jobs_.pop_front();
    ++busy_;
    lock.unlock();
    try {
      job();
    } catch (const std::exception& e) {  // jobs report their own errors; this is a last resort
      std::fprintf(stderr, "stratad: background job failed: %s\n", e.what());
    }
    lock.lock();
    --busy_;
    if (jobs_.empty() && busy_ == 0) idle_cv_.notify_all();
  }
}

}  // namespace strata::service
