#pragma once
// The load test's report as JSON: a superset of ghz's (name, endReason, options, date, count,
// total, average, fastest, slowest, rps, errorDistribution, statusCodeDistribution,
// latencyDistribution with p10..p99.9, histogram, details optional; durations in nanoseconds as
// ghz writes them) plus strata's own part: frame counts that add up (sent = received + dropped +
// coalesced + errors), every RPC's status codes by method, time to first frame, fps and
// inter-frame gaps per session, server GPU ms, history resets, session create/delete latency,
// and per-session and per-second series.
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "loadtest_options.h"
#include "loadtest_session.h"

namespace strata::client {

struct RunInfo {
  LoadClock::time_point start, end;
  std::string date;     // RFC 3339, when the run started
  std::string device;   // what the server reported
};

nlohmann::json make_report(const LoadtestOptions& options, const RunInfo& run, const std::vector<SessionResult>& sessions);

// p in [0, 100] of sorted values (nearest rank); 0 for none.
double percentile(const std::vector<double>& sorted, double p);

}  // namespace strata::client
