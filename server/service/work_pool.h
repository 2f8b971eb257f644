#pragma once
// A fixed set of worker threads running posted jobs in order of posting (frame encoding and the
// release of GPU state happen here, off the gRPC threads and off the frame scheduler).
#include <condition_variable>
#include <cstdint>
#include <deque>
#include <functional>
#include <mutex>
#include <thread>
#include <vector>

namespace strata::service {

class WorkPool {
 public:
  explicit WorkPool(uint32_t threads);
  ~WorkPool();  // runs every job already posted, then joins
  WorkPool(const WorkPool&) = delete;
  WorkPool& operator=(const WorkPool&) = delete;

  void post(std::function<void()> job);
  // Blocks until every job posted so far has run.
  void wait_idle();

 private:
  void run();
  std::mutex mu_;
  std::condition_variable cv_, idle_cv_;
  std::deque<std::function<void()>> jobs_;
  uint32_t busy_ = 0;
  bool stop_ = false;
  std::vector<std::thread> threads_;
};

}  // namespace strata::service
