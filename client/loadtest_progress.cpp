#include "loadtest_progress.h"

#include <unistd.h>

#include <algorithm>
#include <cstdio>
#include <string>

namespace strata::client {

LoadtestProgress::LoadtestProgress(const LoadtestOptions& options, const LoadProgress& counters, LoadClock::time_point start)
    : options_(options), counters_(counters), start_(start), terminal_(::isatty(STDERR_FILENO) == 1) {
  thread_ = std::thread([this] {
    const auto period = terminal_ ? std::chrono::milliseconds(200) : std::chrono::milliseconds(5000);
    auto next = LoadClock::now() + period;
    while (!stop_.load()) {
      std::this_thread::sleep_for(std::chrono::milliseconds(50));
      if (LoadClock::now() < next) continue;
      next += period;
      show(false);
    }
  });
}

LoadtestProgress::~LoadtestProgress() {
  stop_ = true;
  thread_.join();
  show(true);
}

void LoadtestProgress::show(bool last) {
  const double t = std::chrono::duration<double>(LoadClock::now() - start_).count();
  const uint64_t sent = counters_.sent.load(), received = counters_.received.load(), errors = counters_.errors.load();
  // Done: the larger of the share of frames requested and the share of the duration passed.
  double done = 0.0;
  if (options_.total > 0) done = double(counters_.answered.load() + errors) / double(options_.total);
  if (options_.duration_s > 0.0) done = std::max(done, t / options_.duration_s);
  done = std::clamp(last ? 1.0 : done, 0.0, 1.0);
  const double fps = t > 0.0 ? double(received) / t : 0.0;
  char line[160];
  if (terminal_) {
    constexpr int k_width = 30;
    const int filled = int(done * k_width);
    std::string bar = std::string(size_t(filled), '#') + std::string(size_t(k_width - filled), '.');
    std::snprintf(line, sizeof line, "\r[%s] %3d%%  %6.1f s  sent %llu  frames %llu  %.1f fps  errors %llu", bar.c_str(), int(done * 100),
                  t, (unsigned long long)sent, (unsigned long long)received, fps, (unsigned long long)errors);
    std::fputs(line, stderr);
    if (last) std::fputs("\n", stderr);
  } else {
    std::snprintf(line, sizeof line, "loadtest: %3d%% %.1f s sent %llu frames %llu %.1f fps errors %llu\n", int(done * 100), t,
                  (unsigned long long)sent, (unsigned long long)received, fps, (unsigned long long)errors);
    std::fputs(line, stderr);
  }
  std::fflush(stderr);
}

}  // namespace strata::client
