// `strata eval` end to end: a real `stratad serve` process and the real client on a tiny image.
// The three files are written, every number in them is finite, the CSV has one row per run and
// frame, equal-time pt runs are there, a second run takes every reference from the server's cache,
// and unknown scenes or methods are refused before any work.
#include <algorithm>
#include <array>
#include <cmath>
#include <cstdlib>
#include <fstream>
#include <map>
#include <set>
#include <sstream>

#include <nlohmann/json.hpp>

#include "process.h"

namespace strata::test {
namespace {

namespace fs = std::filesystem;

std::string read_file(const fs::path& p) {
  std::ifstream in(p, std::ios::binary);
  return std::string(std::istreambuf_iterator<char>(in), {});
}

std::vector<std::string> eval_args(const std::string& address, const fs::path& out) {
  return {strata_path(), "eval", "--server", address, "--scenes", "cornell", "--methods", "pt,restir-gather", "--frames", "3",
          "--width", "16", "--height", "16", "--reference-spp", "32", "--seed", "1", "--equal-time", "--out", out.string()};
}

// Every number in `j` is finite (NaN and infinities would have been written as null).
void expect_finite_numbers(const nlohmann::json& j, const std::string& at = "") {
  if (j.is_number_float()) {
    EXPECT_TRUE(std::isfinite(j.get<double>())) << at;
  }
  if (j.is_object())
    for (const auto& [k, v] : j.items()) expect_finite_numbers(v, at + "." + k);
  if (j.is_array())
    for (size_t i = 0; i < j.size(); ++i) expect_finite_numbers(j[i], at + "[" + std::to_string(i) + "]");
}

std::vector<std::vector<std::string>> csv_rows(const std::string& text) {
  std::vector<std::vector<std::string>> rows;
  std::stringstream lines(text);
  for (std::string line; std::getline(lines, line);) {
    std::vector<std::string> cells;
    std::stringstream ss(line);
    for (std::string cell; std::getline(ss, cell, ',');) cells.push_back(cell);
    if (!line.empty() && line.back() == ',') cells.emplace_back();
    rows.push_back(std::move(cells));
  }
  return rows;
}

void check_results(const fs::path& out) {
  for (const char* name : {"results.csv", "results.json", "report.html"})
    EXPECT_GT(fs::file_size(out / name), 0u) << name;
  EXPECT_NE(read_file(out / "report.html").find("<html"), std::string::npos);

  // results.csv: pt, restir-gather and the equal-time pt run, 3 frames each.
  const auto rows = csv_rows(read_file(out / "results.csv"));
  ASSERT_EQ(rows.size(), 1u + 3u * 3u) << read_file(out / "results.csv");
  const auto& header = rows[0];
  std::map<std::string, size_t> col;
  for (size_t i = 0; i < header.size(); ++i) col[header[i]] = i;
  for (const char* c : {"scene", "method", "spp", "equal_time_pt", "frame", "gpu_ms", "relmse", "mape", "flip", "relmse_luminance"})
    ASSERT_TRUE(col.count(c)) << "no column " << c;
  std::map<std::string, std::set<std::string>> frames_by_run;
  for (size_t r = 1; r < rows.size(); ++r) {
    const auto& row = rows[r];
    ASSERT_EQ(row.size(), header.size()) << "row " << r;
    EXPECT_EQ(row[col["scene"]], "cornell");
    frames_by_run[row[col["method"]] + (row[col["equal_time_pt"]] == "true" ? " (equal time)" : "")].insert(row[col["frame"]]);
    for (const char* c : {"gpu_ms", "cumulative_ms", "relmse", "mape", "flip", "relmse_luminance"}) {
      char* end = nullptr;
      const double v = std::strtod(row[col[c]].c_str(), &end);
      EXPECT_TRUE(end && *end == '\0' && !row[col[c]].empty()) << c << " = '" << row[col[c]] << "' in row " << r;
      EXPECT_TRUE(std::isfinite(v) && v >= 0.0) << c << " = " << v << " in row " << r;
    }
  }
  const std::set<std::string> all_frames = {"0", "1", "2"};
  EXPECT_EQ(frames_by_run.size(), 3u);
  EXPECT_EQ(frames_by_run["pt"], all_frames);
  EXPECT_EQ(frames_by_run["restir-gather"], all_frames);
  EXPECT_EQ(frames_by_run["pt (equal time)"], all_frames);

  const auto doc = nlohmann::json::parse(read_file(out / "results.json"));
  expect_finite_numbers(doc);
  ASSERT_EQ(doc["runs"].size(), 3u);
  for (const auto& run : doc["runs"])
    for (const auto& f : run["frames"]) {
      EXPECT_GT(f["whole"]["relmse"].get<double>(), 0.0);
      EXPECT_FALSE(f["pass_ms"].empty());
    }
  ASSERT_EQ(doc["equal_time"].size(), 1u);
  const auto& et = doc["equal_time"][0];
  EXPECT_EQ(et["method"], "restir-gather");
  EXPECT_GE(et["pt_spp"].get<int>(), 1);
  for (const char* m : {"relmse", "mape", "flip"}) EXPECT_GT(et["ratio"][m].get<double>(), 0.0) << m;
  EXPECT_NEAR(et["relmse_ratio_at_equal_ms"].get<double>(),
              et["ratio"]["relmse"].get<double>() * et["method_median_ms"].get<double>() / et["pt_median_ms"].get<double>(), 1e-9);
  ASSERT_EQ(doc["insets"].size(), 1u);
  std::set<std::string> insets;
  for (const auto& name : doc["insets"][0]["images"]) insets.insert(name.get<std::string>());
  EXPECT_EQ(insets, (std::set<std::string>{"reference", "pt", "restir-gather", "error:pt", "error:restir-gather"}));
  EXPECT_EQ(doc["meta"]["references"].size(), 3u);
  for (const auto& r : doc["meta"]["references"]) EXPECT_EQ(r["spp"], 32);
}

TEST(EvalTest, StrataEvalWritesTheReportAndReusesCachedReferences) {
  TempDir dir;
  Daemon daemon({"--reference-cache", (dir.path / "cache").string()});
  const auto first = run_process(eval_args(daemon.address(), dir.path / "first"), 300s);
  ASSERT_EQ(first.exit_code, 0) << first.output;
  check_results(dir.path / "first");
  const auto meta1 = nlohmann::json::parse(read_file(dir.path / "first" / "results.json"))["meta"];
  // cornell's camera is keyed still, but its sampled frame states may differ in the last bit:
  // frames whose states are equal share one reference (the cache is keyed by content).
  std::set<std::string> keys;
  for (const auto& r : meta1["references"]) keys.insert(r["cache_key"].get<std::string>());
  EXPECT_EQ(meta1["references_rendered"].get<size_t>(), keys.size());
  EXPECT_EQ(meta1["reference_cache_hits"].get<size_t>(), 3 - keys.size());
  EXPECT_NE(meta1["command_line"].get<std::string>().find("--equal-time"), std::string::npos);

  const auto second = run_process(eval_args(daemon.address(), dir.path / "second"), 300s);
  ASSERT_EQ(second.exit_code, 0) << second.output;
  check_results(dir.path / "second");
  const auto doc2 = nlohmann::json::parse(read_file(dir.path / "second" / "results.json"));
  EXPECT_EQ(doc2["meta"]["reference_cache_hits"], 3);
  EXPECT_EQ(doc2["meta"]["references_rendered"], 0);
  for (const auto& r : doc2["meta"]["references"]) EXPECT_TRUE(r["cached"].get<bool>());
  // Same seeds and references: the methods' errors are the same.
  const auto doc1 = nlohmann::json::parse(read_file(dir.path / "first" / "results.json"));
  EXPECT_EQ(doc1["runs"][0]["frames"][2]["whole"], doc2["runs"][0]["frames"][2]["whole"]);
  EXPECT_EQ(size_t(std::distance(fs::directory_iterator(dir.path / "cache"), fs::directory_iterator{})), keys.size());

  // The ReSTIR flags reach the sessions (the restir-gather errors change) and the record.
  auto args = eval_args(daemon.address(), dir.path / "third");
  for (const char* a : {"--suffix", "fail", "--spatial-neighbors", "3", "--spatial-radius", "5", "--no-spatial"}) args.push_back(a);
  const auto third = run_process(args, 300s);
  ASSERT_EQ(third.exit_code, 0) << third.output;
  const auto doc3 = nlohmann::json::parse(read_file(dir.path / "third" / "results.json"));
  // In the option table's order: the user options, then the experimental ones.
  EXPECT_EQ(doc3["meta"]["restir_options"], "--no-spatial --spatial-neighbors 3 --spatial-radius 5 --suffix fail");
  EXPECT_NE(doc3["meta"]["command_line"].get<std::string>().find("--no-spatial --spatial-neighbors 3 --spatial-radius 5 --suffix fail"),
            std::string::npos);
  auto gather = [](const nlohmann::json& doc) {
    for (const auto& run : doc["runs"])
      if (run["method"] == "restir-gather" && !run["equal_time_pt"].get<bool>()) return run["frames"][2]["whole"];
    return nlohmann::json();
  };
  ASSERT_FALSE(gather(doc3).is_null());
  EXPECT_NE(gather(doc3), gather(doc1)) << "spatial reuse off must change restir-gather's image";
}

TEST(EvalTest, UnknownScenesAndMethodsAreRefusedBeforeAnyWork) {
  TempDir dir;
  Daemon daemon({"--reference-cache", (dir.path / "cache").string()});
  auto args = eval_args(daemon.address(), dir.path / "out");
  args[5] = "cornell,no-such-scene";
  const auto scene = run_process(args, k_render_deadline);
  EXPECT_NE(scene.exit_code, 0);
  EXPECT_NE(scene.output.find("--scenes: 'no-such-scene' is not a scene of"), std::string::npos) << scene.output;
  EXPECT_NE(scene.output.find("cornell"), std::string::npos) << scene.output;

  args = eval_args(daemon.address(), dir.path / "out");
  args[7] = "pt,magic";
  const auto method = run_process(args, k_render_deadline);
  EXPECT_NE(method.exit_code, 0);
  EXPECT_NE(method.output.find("--methods: 'magic' is not available on"), std::string::npos) << method.output;
  EXPECT_NE(method.output.find("restir-gather"), std::string::npos) << method.output;

  args = eval_args(daemon.address(), dir.path / "out");
  args[9] = "0";
  const auto frames = run_process(args, k_render_deadline);
  EXPECT_NE(frames.exit_code, 0);
  EXPECT_NE(frames.output.find("--frames must be at least 1"), std::string::npos) << frames.output;
  EXPECT_FALSE(fs::exists(dir.path / "out")) << "nothing was started";
  EXPECT_FALSE(fs::exists(dir.path / "cache"));
}

}  // namespace
}  // namespace strata::test

namespace strata::test {
namespace {

double median_of(std::vector<double> v) {
  std::sort(v.begin(), v.end());
  const size_t n = v.size();
  return n % 2 ? v[n / 2] : 0.5 * (v[n / 2 - 1] + v[n / 2]);
}

// --timing-rounds: every run (the methods', the equal-time pt runs) is timed R times, its time is
// the median of the rounds' median frame times, and the equal-time comparison uses those.
TEST(EvalTest, TimingRoundsTimeEveryRunAndUseTheirMedian) {
  TempDir dir;
  Daemon daemon({"--reference-cache", (dir.path / "cache").string()});
  auto args = eval_args(daemon.address(), dir.path / "rounds");
  for (const char* a : {"--timing-rounds", "3"}) args.push_back(a);
  const auto result = run_process(args, 300s);
  ASSERT_EQ(result.exit_code, 0) << result.output;
  const auto doc = nlohmann::json::parse(read_file(dir.path / "rounds" / "results.json"));
  EXPECT_EQ(doc["meta"]["timing_rounds"], 3);
  EXPECT_NE(doc["meta"]["command_line"].get<std::string>().find("--timing-rounds 3"), std::string::npos);
  std::map<std::string, double> time_of;  // method, or "pt@spp" for equal-time pt runs
  for (const auto& run : doc["runs"]) {
    ASSERT_EQ(run["round_ms"].size(), 3u) << run["method"];
    ASSERT_EQ(run["frames"].size(), 3u) << "the errors are the first round's frames";
    const auto rounds = run["round_ms"].get<std::vector<double>>();
    for (double ms : rounds) EXPECT_GT(ms, 0.0);
    ASSERT_EQ(run["round_pass_ms"].size(), 3u) << run["method"];  // each round's median ms per pass
    for (const auto& passes : run["round_pass_ms"]) {
      EXPECT_FALSE(passes.empty()) << run["method"];
      for (const auto& [pass, ms] : passes.items()) EXPECT_GE(ms.get<double>(), 0.0) << pass;
    }
    const std::string key = run["equal_time_pt"].get<bool>() ? "pt@" + std::to_string(run["spp"].get<int>()) : run["method"].get<std::string>();
    time_of[key] = median_of(rounds);
  }
  ASSERT_EQ(doc["equal_time"].size(), 1u);
  const auto& et = doc["equal_time"][0];
  EXPECT_DOUBLE_EQ(et["method_median_ms"].get<double>(), time_of["restir-gather"]);
  EXPECT_DOUBLE_EQ(et["pt_median_ms"].get<double>(), time_of["pt@" + std::to_string(et["pt_spp"].get<int>())]);
  EXPECT_DOUBLE_EQ(doc["meta"]["pt_ms_per_spp"]["cornell"].get<double>(), time_of["pt"]);
  // The later rounds play the methods interleaved, frame f of each in turn, starting each frame one
  // run further along: the progress lines of the timed frames (one per frame, not a terminal) give
  // frame f of pt and restir-gather together, pt first on frame 0 and restir-gather first on frame 1.
  std::vector<std::string> timed;  // "method frame" of each "(timing)" line, in order
  std::istringstream lines(result.output);
  for (std::string line; std::getline(lines, line);) {
    if (line.find("(timing)") == std::string::npos || line.find("spp 1 ") == std::string::npos) continue;
    const auto at = line.find("cornell ");
    ASSERT_NE(at, std::string::npos) << line;
    std::istringstream words(line.substr(at));
    std::string scene, method, spp_word, spp, frame_word, frame;
    words >> scene >> method >> spp_word >> spp >> frame_word >> frame;
    timed.push_back(method + " " + frame);
  }
  ASSERT_EQ(timed.size(), 2u * 2u * 3u) << result.output;  // 2 rounds x 2 methods x 3 frames
  for (size_t i = 0; i < timed.size(); i += 2) {
    const std::string frame = std::to_string((i / 2) % 3);
    std::array<std::string, 2> pair = {timed[i], timed[i + 1]};
    if ((i / 2) % 3 == 1) std::swap(pair[0], pair[1]);
    if ((i / 2) % 3 != 2) {
      EXPECT_EQ(pair[0], "pt " + frame) << i;
      EXPECT_EQ(pair[1], "restir-gather " + frame) << i;
    } else {
      std::sort(pair.begin(), pair.end());
      EXPECT_EQ(pair[0], "pt " + frame) << i;
      EXPECT_EQ(pair[1], "restir-gather " + frame) << i;
    }
  }

  // A daemon that holds one session at a time: the interleaved rounds play one run after the other.
  Daemon single({"--max-sessions", "1", "--reference-cache", (dir.path / "cache").string()});
  args = eval_args(single.address(), dir.path / "single");
  for (const char* a : {"--timing-rounds", "2"}) args.push_back(a);
  const auto one_at_a_time = run_process(args, 300s);
  ASSERT_EQ(one_at_a_time.exit_code, 0) << one_at_a_time.output;
  for (const auto& run : nlohmann::json::parse(read_file(dir.path / "single" / "results.json"))["runs"])
    EXPECT_EQ(run["round_ms"].size(), 2u) << run["method"];

  args = eval_args(daemon.address(), dir.path / "bad");
  for (const char* a : {"--timing-rounds", "0"}) args.push_back(a);
  const auto bad = run_process(args, k_render_deadline);
  EXPECT_NE(bad.exit_code, 0);
  EXPECT_NE(bad.output.find("--timing-rounds"), std::string::npos) << bad.output;
}

// --score-from N: every method plays frames 0..N-1 (its history builds up) but only the later
// frames are scored and timed, against references of those frames only. A scored frame equals the
// same frame of a run that scores everything (same seed, same frames played before it).
TEST(EvalTest, ScoreFromPlaysTheWarmUpWithoutScoringIt) {
  TempDir dir;
  Daemon daemon({"--reference-cache", (dir.path / "cache").string()});
  auto all = eval_args(daemon.address(), dir.path / "all");
  all[9] = "4";
  ASSERT_EQ(run_process(all, 300s).exit_code, 0);
  auto warm = eval_args(daemon.address(), dir.path / "warm");
  warm[9] = "4";
  for (const char* a : {"--score-from", "2"}) warm.push_back(a);
  const auto result = run_process(warm, 300s);
  ASSERT_EQ(result.exit_code, 0) << result.output;

  const auto doc_all = nlohmann::json::parse(read_file(dir.path / "all" / "results.json"));
  const auto doc = nlohmann::json::parse(read_file(dir.path / "warm" / "results.json"));
  EXPECT_EQ(doc["meta"]["score_from"], 2);
  EXPECT_NE(doc["meta"]["command_line"].get<std::string>().find("--score-from 2"), std::string::npos);
  EXPECT_EQ(doc["meta"]["references"].size(), 2u) << "no reference for the warm-up frames";
  const auto frame_of = [](const nlohmann::json& d, const std::string& method, int frame) {
    for (const auto& run : d["runs"])
      if (run["method"] == method && !run["equal_time_pt"].get<bool>())
        for (const auto& f : run["frames"])
          if (f["frame"] == frame) return f;
    return nlohmann::json();
  };
  for (const auto& run : doc["runs"]) {
    ASSERT_EQ(run["frames"].size(), 2u) << run["method"];
    EXPECT_EQ(run["frames"][0]["frame"], 2);
    EXPECT_EQ(run["frames"][1]["frame"], 3);
  }
  ASSERT_FALSE(frame_of(doc, "restir-gather", 3).is_null());
  EXPECT_EQ(frame_of(doc, "restir-gather", 3)["whole"], frame_of(doc_all, "restir-gather", 3)["whole"])
      << "the warm-up frames must be played: frame 3 carries their history";

  auto bad = eval_args(daemon.address(), dir.path / "bad");
  for (const char* a : {"--score-from", "3"}) bad.push_back(a);
  const auto refused = run_process(bad, k_render_deadline);
  EXPECT_NE(refused.exit_code, 0);
  EXPECT_NE(refused.output.find("--score-from = 3 leaves no frame to score"), std::string::npos) << refused.output;
  EXPECT_FALSE(fs::exists(dir.path / "bad"));
}

// --methods NAME:FLAG=VALUE: an entry carries ReSTIR flags of its own over those given to all, so
// variants of one method run (and are timed) side by side. The variant's frames equal those of the
// method run with the same flags given to all (the errors are deterministic for the seed), and
// differ from the entry without them; an entry with a flag that does not exist is refused before
// any work. --save-frames writes each run's scored frames and the references.
TEST(EvalTest, MethodEntriesCarryFlagsOfTheirOwn) {
  TempDir dir;
  Daemon daemon({"--reference-cache", (dir.path / "cache").string()});
  auto both = eval_args(daemon.address(), dir.path / "both");
  both[7] = "restir-gather,restir-gather:spatial-neighbors=1";
  both.erase(std::find(both.begin(), both.end(), "--equal-time"));
  for (const char* a : {"--spatial-neighbors", "4", "--save-frames"}) both.push_back(a);
  const auto result = run_process(both, 300s);
  ASSERT_EQ(result.exit_code, 0) << result.output;
  auto one = eval_args(daemon.address(), dir.path / "one");
  one[7] = "restir-gather";
  one.erase(std::find(one.begin(), one.end(), "--equal-time"));
  for (const char* a : {"--spatial-neighbors", "1"}) one.push_back(a);
  ASSERT_EQ(run_process(one, 300s).exit_code, 0);

  const auto errors_of = [](const nlohmann::json& d, const std::string& method) {
    std::vector<nlohmann::json> out;
    for (const auto& run : d["runs"])
      if (run["method"] == method)
        for (const auto& f : run["frames"]) out.push_back(f["whole"]);
    return out;
  };
  const auto doc = nlohmann::json::parse(read_file(dir.path / "both" / "results.json"));
  const auto doc_one = nlohmann::json::parse(read_file(dir.path / "one" / "results.json"));
  ASSERT_EQ(doc["runs"].size(), 2u);
  const auto variant = errors_of(doc, "restir-gather:spatial-neighbors=1");
  ASSERT_EQ(variant.size(), 3u) << "the entry is the run's name";
  EXPECT_EQ(variant, errors_of(doc_one, "restir-gather")) << "the entry's flag overrides the common --spatial-neighbors 4";
  EXPECT_NE(variant, errors_of(doc, "restir-gather"));
  // --save-frames: every scored frame of each run and its reference, as EXR.
  for (const char* run : {"reference", "restir-gather", "restir-gather_spatial-neighbors=1"})
    for (const char* frame : {"frame_0000.exr", "frame_0001.exr", "frame_0002.exr"}) {
      const fs::path p = dir.path / "both" / "frames" / "cornell" / run / frame;
      ASSERT_TRUE(fs::exists(p)) << p;
      EXPECT_GT(fs::file_size(p), 100u) << p;
    }

  auto bad = eval_args(daemon.address(), dir.path / "bad");
  bad[7] = "pt,restir-gather:no-such-flag=3";
  const auto refused = run_process(bad, k_render_deadline);
  EXPECT_NE(refused.exit_code, 0);
  EXPECT_NE(refused.output.find("--methods: 'restir-gather:no-such-flag=3'"), std::string::npos) << refused.output;
  EXPECT_FALSE(fs::exists(dir.path / "bad"));
  bad[7] = "restir-gather::";
  const auto empty = run_process(bad, k_render_deadline);
  EXPECT_NE(empty.exit_code, 0);
  EXPECT_NE(empty.output.find("has an empty flag"), std::string::npos) << empty.output;
}

}  // namespace
}  // namespace strata::test
