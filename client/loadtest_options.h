#pragma once
// `strata loadtest`'s settings (shaped after ghz's flags) and their checks: every violation names
// the flag and its limit. The run itself is bounded in count and time by these limits.
#include <chrono>
#include <cstdint>
#include <string>
#include <vector>

#include "restir_flags.h"
#include "strata/v1/render.pb.h"

namespace strata::client {

struct LoadSchedule {
  std::string kind = "const";  // const | step | line
  double start = 0.0, step = 0.0, end = 0.0;  // frames/s (step: per step, line: per second)
  double step_duration_s = 1.0;               // step: seconds per step
};

struct LoadtestOptions {
  std::string server = "127.0.0.1:50051";
  std::string name;                      // the report's name (ghz --name)
  std::vector<std::string> tags;         // key=value (ghz --tags, here as repeated key=value)
  uint32_t concurrency = 1;              // -c: sessions streaming at once
  uint64_t total = 0;                    // -n: frames requested in all (0: unset)
  double duration_s = 0.0;               // -z: seconds (0: unset)
  double rps = 0.0;                      // --rps: frames/s over every session (0: as fast as each session gets answers)
  uint32_t connections = 1;              // channels the sessions share round-robin
  double timeout_s = 20.0;               // --timeout: a unary call, or a frame's wait for its answer
  uint32_t skip_first = 0;               // frames of each session left out of the latency statistics
  LoadSchedule schedule;
  bool details = false;                  // write every frame request into the JSON (ghz's details)
  std::string out = "out/loadtest";

  // What each session asks for, as `strata stream` does.
  std::string scene = "cornell";
  std::string method = "pt";
  uint32_t width = 64, height = 64, spp = 1, seed = 0;
  RestirFlags restir;  // the option table's flags that were given (restir_flags.h)
  std::string encodings = "raw";
  std::string camera_path;

  // The limits the checks hold the flags to.
  static constexpr uint32_t k_max_concurrency = 64;
  static constexpr uint64_t k_max_total = 1'000'000;
  static constexpr double k_max_duration_s = 3600.0;
  static constexpr double k_max_rps = 10'000.0;
  static constexpr double k_max_timeout_s = 600.0;

  // Throws std::invalid_argument naming the flag and the limit.
  void validate() const;
  bool open_loop() const { return rps > 0.0 || schedule.kind != "const"; }
  // The paced rate (frames/s) `t` seconds into the run (open loop only).
  double rate_at(double t) const;
};

std::vector<v1::ImageEncoding> parse_encoding_list(const std::string& list);  // "raw,png"; --encodings in errors

}  // namespace strata::client
