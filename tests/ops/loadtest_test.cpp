// `strata loadtest` against a real stratad on 127.0.0.1: the frame counts add up (sent = received
// + dropped + coalesced + errors), report.json carries ghz's field names, RESOURCE_EXHAUSTED is
// counted (not a crash) when -c exceeds max_sessions, --rps holds the rate within 10% when the
// server keeps up (pt at 32x32, a low rate, so that a loaded 2-core machine keeps up), and bad
// flags are refused naming the flag and its limit. report.html draws in headless Chromium.
#include <gtest/gtest.h>

#include <nlohmann/json.hpp>

#include <unistd.h>

#include "cdp_pipe.h"
#include "harness.h"
#include "ops_util.h"

namespace strata::test {
namespace {

using nlohmann::json;

std::vector<std::string> loadtest_args(const std::string& address, const std::filesystem::path& out, std::vector<std::string> more) {
  std::vector<std::string> a = {strata_path(), "loadtest", "--server", address, "--scene", "cornell", "--method", "pt",
                                "--width", "16", "--height", "16", "--out", out.string(), "--timeout", "60"};
  a.insert(a.end(), more.begin(), more.end());
  return a;
}

json run_loadtest(const std::vector<std::string>& args, const std::filesystem::path& out) {
  const auto r = run_process(args, 120s);
  EXPECT_EQ(r.exit_code, 0) << r.output;
  const std::string text = read_text(out / "report.json");
  if (text.empty()) {
    ADD_FAILURE() << "no report.json:\n" << r.output;
    return json::object();
  }
  return json::parse(text);
}

uint64_t frames_field(const json& r, const char* name) { return r["strata"]["frames"][name].get<uint64_t>(); }

void expect_counts_add_up(const json& r) {
  EXPECT_EQ(frames_field(r, "inputs_sent"), frames_field(r, "frames_received") + frames_field(r, "frames_dropped") +
                                                frames_field(r, "inputs_coalesced") + frames_field(r, "errors"))
      << r["strata"]["frames"].dump();
  EXPECT_EQ(r["count"].get<uint64_t>(), frames_field(r, "inputs_sent"));
}

TEST(LoadtestTest, CountsAddUpAndTheReportHasGhzFields) {
  TempDir dir;
  Daemon daemon;
  const json r = run_loadtest(loadtest_args(daemon.address(), dir.path, {"-c", "2", "-n", "12", "--connections", "2", "--details",
                                                                          "--name", "smoke", "--tags", "suite=ops"}),
                              dir.path);
  ASSERT_TRUE(r.contains("strata"));
  // ghz's report fields (runner/reporter.go), with its types: durations in integer nanoseconds.
  for (const char* f : {"name", "endReason", "options", "date", "count", "total", "average", "fastest", "slowest", "rps",
                        "errorDistribution", "statusCodeDistribution", "latencyDistribution", "histogram", "details"})
    EXPECT_TRUE(r.contains(f)) << "missing ghz field " << f;
  EXPECT_EQ(r["name"], "smoke");
  EXPECT_EQ(r["tags"]["suite"], "ops");
  EXPECT_EQ(r["endReason"], "normal");
  EXPECT_TRUE(r["total"].is_number_integer());
  EXPECT_TRUE(r["average"].is_number_integer());
  EXPECT_GT(r["fastest"].get<int64_t>(), 0);
  EXPECT_LE(r["fastest"].get<int64_t>(), r["average"].get<int64_t>());
  EXPECT_LE(r["average"].get<int64_t>(), r["slowest"].get<int64_t>());
  EXPECT_EQ(r["count"], 12);
  EXPECT_EQ(r["statusCodeDistribution"]["OK"], 12);
  ASSERT_EQ(r["latencyDistribution"].size(), 8u);
  EXPECT_EQ(r["latencyDistribution"][0]["percentage"], 10);
  EXPECT_EQ(r["latencyDistribution"][7]["percentage"], 99.9);
  for (const auto& d : r["latencyDistribution"]) EXPECT_TRUE(d["latency"].is_number_integer());
  ASSERT_EQ(r["histogram"].size(), 10u);
  uint64_t in_histogram = 0;
  for (const auto& b : r["histogram"]) {
    EXPECT_TRUE(b.contains("mark") && b.contains("frequency"));
    in_histogram += b["count"].get<uint64_t>();
  }
  EXPECT_EQ(in_histogram, 12u);
  ASSERT_EQ(r["details"].size(), 12u);
  for (const char* f : {"timestamp", "latency", "error", "status"}) EXPECT_TRUE(r["details"][0].contains(f)) << f;
  expect_counts_add_up(r);
  const auto& s = r["strata"];
  EXPECT_EQ(s["rpcStatusCodes"]["CreateSession"]["OK"], 2);
  EXPECT_EQ(s["rpcStatusCodes"]["Stream"]["OK"], 2);
  EXPECT_EQ(s["rpcStatusCodes"]["DeleteSession"]["OK"], 2);
  ASSERT_EQ(s["per_session"].size(), 2u);
  for (const auto& p : s["per_session"]) {
    EXPECT_GT(p["ttff_ms"].get<double>(), 0.0);
    EXPECT_GT(p["fps"].get<double>(), 0.0);
    EXPECT_EQ(p["history_resets"], 1);  // the first frame of each session
  }
  EXPECT_EQ(s["history_resets"], 2);
  EXPECT_GT(s["server_gpu_ms"]["mean"].get<double>(), 0.0);
  EXPECT_FALSE(s["per_second"].empty());
  // report.html is self-contained: uPlot inlined, nothing fetched.
  const std::string html = read_text(dir.path / "report.html");
  EXPECT_NE(html.find("uPlot"), std::string::npos);
  EXPECT_EQ(html.find("<script src"), std::string::npos);
  EXPECT_EQ(html.find("http://"), std::string::npos);

  // And it draws its three plots in headless Chromium with no network and nothing on the console.
  const std::string chromium = tool_path("STRATA_CHROMIUM", "/usr/bin/chromium");
  ASSERT_EQ(::access(chromium.c_str(), X_OK), 0) << chromium << " is not installed (deploy/install-deps.sh)";
  Chromium browser(chromium, dir.path, 1200, 1000);
  browser.open("file://" + (dir.path / "report.html").string());
  nlohmann::json state;
  EXPECT_TRUE(wait_until([&] {
    state = browser.evaluate("document.body ? [document.body.dataset.plots || '', document.title] : ['', '']");
    return state[0] == "3" && state[1].get<std::string>().ends_with("[ready]");
  }, 30s)) << state.dump();
  for (const auto& m : browser.page_messages()) ADD_FAILURE() << "report.html wrote to the console: " << m;
}

TEST(LoadtestTest, ResourceExhaustedIsCountedWhenSessionsExceedTheLimit) {
  TempDir dir;
  Daemon daemon({"--max-sessions", "2"});
  const json r = run_loadtest(loadtest_args(daemon.address(), dir.path, {"-c", "3", "-n", "9"}), dir.path);
  ASSERT_TRUE(r.contains("strata"));
  const auto& codes = r["strata"]["rpcStatusCodes"]["CreateSession"];
  EXPECT_EQ(codes["OK"], 2) << codes.dump();
  EXPECT_EQ(codes["RESOURCE_EXHAUSTED"], 1) << codes.dump();
  bool named = false;
  for (const auto& [message, n] : r["errorDistribution"].items())
    named = named || (message.find("RESOURCE_EXHAUSTED") != std::string::npos && message.find("max_sessions") != std::string::npos);
  EXPECT_TRUE(named) << r["errorDistribution"].dump();
  EXPECT_EQ(r["count"], 9);  // the two sessions that got in took every frame
  expect_counts_add_up(r);
}

TEST(LoadtestTest, RpsHoldsTheRateWithinTenPercent) {
  TempDir dir;
  Daemon daemon;
  constexpr double k_rps = 8.0, k_seconds = 5.0;
  auto args = loadtest_args(daemon.address(), dir.path, {"-c", "2", "-z", "5", "--rps", "8"});
  args[9] = "32";  // --width
  args[11] = "32";  // --height
  const json r = run_loadtest(args, dir.path);
  ASSERT_TRUE(r.contains("strata"));
  const double count = r["count"].get<double>();
  EXPECT_NEAR(count, k_rps * k_seconds, 0.1 * k_rps * k_seconds);
  const double sent_rate = r["strata"]["sent_per_second"].get<double>();
  EXPECT_NEAR(sent_rate, k_rps, 0.1 * k_rps) << "the pacer did not hold --rps";
  EXPECT_EQ(r["strata"]["frames"]["errors"], 0);
  expect_counts_add_up(r);
}

TEST(LoadtestTest, StepScheduleRaisesTheRateEachStep) {
  TempDir dir;
  Daemon daemon;
  // 4 frames/s, +4 every second, for 3 s: 4 + 8 + 12 frames scheduled, by the second they were due.
  const json r = run_loadtest(loadtest_args(daemon.address(), dir.path, {"-c", "2", "-z", "3", "--load-schedule", "step",
                                                                          "--load-start", "4", "--load-step", "4",
                                                                          "--load-step-duration", "1"}),
                              dir.path);
  ASSERT_TRUE(r.contains("strata"));
  EXPECT_EQ(r["count"], 24);
  const auto& per_second = r["strata"]["per_second"];
  ASSERT_GE(per_second.size(), 3u);
  EXPECT_EQ(per_second[0]["inputs_sent"], 4);
  EXPECT_EQ(per_second[1]["inputs_sent"], 8);
  EXPECT_EQ(per_second[2]["inputs_sent"], 12);
  expect_counts_add_up(r);
}

TEST(LoadtestTest, BadFlagsNameTheFlagAndTheLimit) {
  TempDir dir;
  const auto zero = run_process(loadtest_args("127.0.0.1:1", dir.path, {"-c", "0", "-n", "5"}), 30s);
  EXPECT_NE(zero.exit_code, 0);
  EXPECT_NE(zero.output.find("-c/--concurrency = 0 must be in 1..64"), std::string::npos) << zero.output;
  const auto unbounded = run_process(loadtest_args("127.0.0.1:1", dir.path, {"-c", "1"}), 30s);
  EXPECT_NE(unbounded.exit_code, 0);
  EXPECT_NE(unbounded.output.find("-n/--total"), std::string::npos) << unbounded.output;
  const auto rate = run_process(loadtest_args("127.0.0.1:1", dir.path, {"-n", "5", "--rps", "20000"}), 30s);
  EXPECT_NE(rate.output.find("--rps = 20000 must be in 0..10000"), std::string::npos) << rate.output;
  const auto schedule = run_process(loadtest_args("127.0.0.1:1", dir.path, {"-z", "5", "--load-schedule", "ramp"}), 30s);
  EXPECT_NE(schedule.output.find("--load-schedule = 'ramp' is not one of const, step, line"), std::string::npos) << schedule.output;
}

}  // namespace
}  // namespace strata::test
