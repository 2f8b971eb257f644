#include "progress.h"

#include <cstdio>

#include <unistd.h>

namespace strata::client {

Progress::Progress(uint64_t total, bool terminal) : total_(total), terminal_(terminal), start_(std::chrono::steady_clock::now()) {}

bool Progress::stderr_is_terminal() { return isatty(STDERR_FILENO) == 1; }

void Progress::frame(uint64_t done, uint64_t frame_index, double latency_ms, double gpu_ms, uint64_t dropped,
                     const std::string& detail) {
  ++count_;
  latency_sum_ += latency_ms;
  const double elapsed = std::chrono::duration<double>(std::chrono::steady_clock::now() - start_).count();
  const double fps = elapsed > 0.0 ? double(count_) / elapsed : 0.0;  // frames received per second
  if (terminal_) {
    constexpr int width = 30;
    const int filled = total_ ? int(double(width) * double(done) / double(total_)) : width;
    std::string bar(size_t(filled), '#');
    bar.resize(width, '.');
    std::fprintf(stderr, "\r[%s] %llu/%llu frames  %5.1f fps  latency %6.1f ms (mean %6.1f)  gpu %6.1f ms", bar.c_str(),
                 static_cast<unsigned long long>(done), static_cast<unsigned long long>(total_), fps, latency_ms,
                 latency_sum_ / double(count_), gpu_ms);
  } else {
    std::fprintf(stderr, "frame %llu/%llu  index %llu  latency %.1f ms  gpu %.1f ms  dropped %llu  %.1f fps%s%s\n",
                 static_cast<unsigned long long>(done), static_cast<unsigned long long>(total_),
                 static_cast<unsigned long long>(frame_index), latency_ms, gpu_ms, static_cast<unsigned long long>(dropped), fps,
                 detail.empty() ? "" : "  ", detail.c_str());
  }
  std::fflush(stderr);
}

void Progress::finish() {
  if (terminal_) std::fprintf(stderr, "\n");
}

}  // namespace strata::client
