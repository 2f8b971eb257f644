#pragma once
// Real processes for the tests that need them: `stratad serve` (drain on SIGTERM, server memory
// as the kernel sees it) and the `strata` client. Output goes to a log file; every wait is bounded.
#include <sys/types.h>

#include <chrono>
#include <optional>
#include <string>
#include <vector>

#include "harness.h"

namespace strata::test {

std::string stratad_path();
std::string strata_path();

struct ProcessResult {
  int exit_code = -1;  // -1: killed after the timeout
  std::string output;  // stdout and stderr
};

// Runs a program to completion (killed after `timeout`).
ProcessResult run_process(const std::vector<std::string>& argv, std::chrono::milliseconds timeout);

class Process {
 public:
  explicit Process(const std::vector<std::string>& argv);
  ~Process();  // SIGKILL if still running
  Process(const Process&) = delete;
  Process& operator=(const Process&) = delete;

  pid_t pid() const { return pid_; }
  void signal(int sig) const;
  // The exit status, or nullopt if it is still running after `timeout`.
  std::optional<int> wait_exit(std::chrono::milliseconds timeout);
  std::string output() const;
  uint64_t rss_bytes() const;  // VmRSS from /proc

 private:
  TempDir dir_;
  pid_t pid_ = -1;
  std::optional<int> status_;
};

// `stratad serve --listen 127.0.0.1:0` plus `args`, ready (health SERVING) when constructed; with
// --no-progressive-start unless `args` has --progressive-start.
class Daemon {
 public:
  explicit Daemon(const std::vector<std::string>& args = {});
  const std::string& address() const { return address_; }
  Process& process() { return *process_; }

 private:
  TempDir dir_;
  std::unique_ptr<Process> process_;
  std::string address_;
};

}  // namespace strata::test
