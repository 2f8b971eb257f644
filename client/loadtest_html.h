#pragma once
// The load test's self-contained report.html: uPlot inlined as `strata eval`'s report does (no
// network at view time), with latency over time (p50 and p99 per second), the latency histogram,
// frames per second of each session, and the summary table.
#include <filesystem>

#include <nlohmann/json.hpp>

namespace strata::client {

void write_loadtest_html(const nlohmann::json& report, const std::filesystem::path& path);

}  // namespace strata::client
