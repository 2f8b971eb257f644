#include "loadtest_pacer.h"

namespace strata::client {

Pacer::Pacer(const LoadtestOptions& options, Clock::time_point start) : options_(options), start_(start) {
  if (options.duration_s > 0.0)
    end_ = start + std::chrono::duration_cast<Clock::duration>(std::chrono::duration<double>(options.duration_s));
}

std::optional<Pacer::Clock::time_point> Pacer::next() {
  std::lock_guard lock(mu_);
  if (options_.total > 0 && issued_ >= options_.total) return std::nullopt;
  Clock::time_point t;
  if (options_.open_loop()) {
    t = start_ + std::chrono::duration_cast<Clock::duration>(std::chrono::duration<double>(next_s_));
    next_s_ += 1.0 / options_.rate_at(next_s_);
  } else {
    t = Clock::now();
  }
  if (end_ && t >= *end_) return std::nullopt;
  ++issued_;
  return t;
}

uint64_t Pacer::issued() const {
  std::lock_guard lock(mu_);
  return issued_;
}

}  // namespace strata::client
