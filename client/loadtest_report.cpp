#include "loadtest_report.h"

#include <algorithm>
#include <cmath>
#include <ctime>
#include <map>
#include <optional>

#include "connection.h"

namespace strata::client {
namespace {

using nlohmann::json;

double ms_between(LoadClock::time_point a, LoadClock::time_point b) { return std::chrono::duration<double, std::milli>(b - a).count(); }
int64_t ns(double ms) { return int64_t(std::llround(ms * 1e6)); }

json stats_ms(std::vector<double> v) {
  std::sort(v.begin(), v.end());
  double sum = 0.0;
  for (double x : v) sum += x;
  return {{"count", v.size()},
          {"mean", v.empty() ? 0.0 : sum / double(v.size())},
          {"p50", percentile(v, 50)},
          {"p99", percentile(v, 99)},
          {"max", v.empty() ? 0.0 : v.back()}};
}

// ghz's histogram: ten equal buckets from fastest to slowest, each marked by its upper bound in
// seconds, with its count and its share of the whole.
json histogram(const std::vector<double>& sorted_ms) {
  json out = json::array();
  if (sorted_ms.empty()) return out;
  constexpr int k_buckets = 10;
  const double lo = sorted_ms.front(), hi = sorted_ms.back();
  const double width = (hi - lo) / k_buckets;
  std::vector<uint64_t> counts(k_buckets, 0);
  for (double v : sorted_ms) {
    int b = width > 0.0 ? int((v - lo) / width) : 0;
    counts[size_t(std::clamp(b, 0, k_buckets - 1))]++;
  }
  for (int b = 0; b < k_buckets; ++b)
    out.push_back({{"mark", (lo + width * (b + 1)) / 1000.0},
                   {"count", counts[size_t(b)]},
                   {"frequency", double(counts[size_t(b)]) / double(sorted_ms.size())}});
  return out;
}

std::string rfc3339(std::chrono::system_clock::time_point t) {
  const std::time_t tt = std::chrono::system_clock::to_time_t(t);
  std::tm tm{};
  gmtime_r(&tt, &tm);
  char buf[32];
  std::strftime(buf, sizeof buf, "%Y-%m-%dT%H:%M:%S", &tm);
  const auto ms = std::chrono::duration_cast<std::chrono::milliseconds>(t.time_since_epoch()).count() % 1000;
  char out[48];
  std::snprintf(out, sizeof out, "%s.%03dZ", buf, int(ms));
  return out;
}

}  // namespace

double percentile(const std::vector<double>& sorted, double p) {
  if (sorted.empty()) return 0.0;
  const double rank = std::ceil(p / 100.0 * double(sorted.size()));
  const size_t i = size_t(std::clamp(rank, 1.0, double(sorted.size()))) - 1;
  return sorted[i];
}

json make_report(const LoadtestOptions& o, const RunInfo& run, const std::vector<SessionResult>& sessions) {
  const double total_ms = ms_between(run.start, run.end);
  const auto wall_to_system = [&](LoadClock::time_point t) {
    return std::chrono::system_clock::now() -
           std::chrono::duration_cast<std::chrono::system_clock::duration>(LoadClock::now() - t);
  };

  std::vector<double> latencies;  // every answered input outside the skipped ones
  std::map<std::string, uint64_t> status_codes, errors;
  std::map<std::string, std::map<std::string, uint64_t>> rpc_codes;
  std::vector<double> create_ms, delete_ms, ttff_ms, gaps_ms, gpu_ms, fps;
  uint64_t sent = 0, received = 0, dropped = 0, coalesced = 0, unanswered = 0, resets = 0, own = 0;
  const int seconds = std::max(1, int(std::ceil(total_ms / 1000.0)));
  const size_t n_seconds = size_t(seconds);
  std::vector<std::vector<double>> per_second_latency(n_seconds);
  std::vector<uint64_t> per_second_sent(n_seconds), per_second_frames(n_seconds);
  json per_session = json::array(), details = json::array();
  bool timed_out = false;
  std::optional<LoadClock::time_point> first_sent, last_sent;

  for (const auto& s : sessions) {
    json js = {{"index", s.index}, {"session", s.name}};
    for (const auto& r : s.rpcs) {
      rpc_codes[r.method][status_code_name(r.code)]++;
      if (r.code != grpc::StatusCode::OK && r.method != "Stream")
        errors[r.method + ": " + status_code_name(r.code) + ": " + r.message]++;
      if (r.method == "CreateSession") {
        js["create_ms"] = r.ms;
        if (r.code == grpc::StatusCode::OK) create_ms.push_back(r.ms);
        else js["error"] = status_code_name(r.code) + ": " + r.message;
      }
      if (r.method == "DeleteSession") {
        js["delete_ms"] = r.ms;
        if (r.code == grpc::StatusCode::OK) delete_ms.push_back(r.ms);
      }
      if (r.method == "Stream") js["stream_status"] = status_code_name(r.code);
    }
    timed_out = timed_out || s.timed_out;
    std::vector<double> session_latency;
    uint64_t session_unanswered = 0;
    for (size_t i = 0; i < s.inputs.size(); ++i) {
      const auto& in = s.inputs[i];
      ++sent;
      if (!first_sent || in.sent < *first_sent) first_sent = in.sent;
      if (!last_sent || in.sent > *last_sent) last_sent = in.sent;
      const int sec = std::clamp(int(ms_between(run.start, in.scheduled) / 1000.0), 0, seconds - 1);
      per_second_sent[size_t(sec)]++;
      if (in.answered) {
        status_codes["OK"]++;
        own += in.own_frame ? 1 : 0;
        const double lat = ms_between(in.scheduled, *in.answered);
        if (i >= o.skip_first) {
          latencies.push_back(lat);
          session_latency.push_back(lat);
          per_second_latency[size_t(std::clamp(int(ms_between(run.start, *in.answered) / 1000.0), 0, seconds - 1))].push_back(lat);
        }
        if (o.details)
          details.push_back({{"timestamp", rfc3339(wall_to_system(in.scheduled))}, {"latency", ns(lat)}, {"error", ""}, {"status", "OK"}});
      } else {
        ++unanswered;
        ++session_unanswered;
        const std::string code = status_code_name(s.stream_code);
        status_codes[code]++;
        errors["Stream: " + code + ": " + s.stream_error]++;
        if (o.details)
          details.push_back({{"timestamp", rfc3339(wall_to_system(in.scheduled))}, {"latency", 0}, {"error", s.stream_error}, {"status", code}});
      }
    }
    uint64_t session_dropped = 0, session_coalesced = 0, session_resets = 0;
    std::vector<double> session_gaps, session_gpu;
    for (size_t i = 0; i < s.frames.size(); ++i) {
      const auto& f = s.frames[i];
      ++received;
      session_dropped += f.dropped;
      session_coalesced += f.coalesced;
      session_resets += f.history_reset ? 1 : 0;
      per_second_frames[size_t(std::clamp(int(ms_between(run.start, f.received) / 1000.0), 0, seconds - 1))]++;
      if (i >= o.skip_first) session_gpu.push_back(f.gpu_ms);
      if (i > 0 && i > o.skip_first) session_gaps.push_back(ms_between(s.frames[i - 1].received, f.received));
    }
    dropped += session_dropped;
    coalesced += session_coalesced;
    resets += session_resets;
    gaps_ms.insert(gaps_ms.end(), session_gaps.begin(), session_gaps.end());
    gpu_ms.insert(gpu_ms.end(), session_gpu.begin(), session_gpu.end());
    double session_fps = 0.0;
    if (s.frames.size() >= 2) {
      const double span = ms_between(s.frames.front().received, s.frames.back().received) / 1000.0;
      if (span > 0.0) session_fps = double(s.frames.size() - 1) / span;
      fps.push_back(session_fps);
    }
    if (!s.frames.empty() && s.stream_start) {
      js["ttff_ms"] = ms_between(*s.stream_start, s.frames.front().received);
      ttff_ms.push_back(js["ttff_ms"].get<double>());
    }
    std::sort(session_latency.begin(), session_latency.end());
    std::sort(session_gaps.begin(), session_gaps.end());
    js["inputs_sent"] = s.inputs.size();
    js["frames_received"] = s.frames.size();
    js["frames_dropped"] = session_dropped;
    js["inputs_coalesced"] = session_coalesced;
    js["errors"] = session_unanswered;
    js["history_resets"] = session_resets;
    js["fps"] = session_fps;
    js["latency_ms"] = {{"p50", percentile(session_latency, 50)}, {"p99", percentile(session_latency, 99)}};
    js["inter_frame_gap_ms"] = {{"p50", percentile(session_gaps, 50)}, {"p99", percentile(session_gaps, 99)}};
    js["gpu_ms"] = stats_ms(session_gpu);
    per_session.push_back(std::move(js));
  }

  std::vector<double> sorted = latencies;
  std::sort(sorted.begin(), sorted.end());
  double sum = 0.0;
  for (double v : sorted) sum += v;

  json r;
  r["name"] = o.name.empty() ? "strata loadtest " + o.method + " " + std::to_string(o.width) + "x" + std::to_string(o.height) : o.name;
  r["endReason"] = timed_out ? "timeout" : "normal";
  json tags = json::object();
  for (const auto& t : o.tags) {
    const auto eq = t.find('=');
    tags[t.substr(0, eq)] = eq == std::string::npos ? "" : t.substr(eq + 1);
  }
  r["tags"] = tags;
  r["options"] = {{"host", o.server}, {"call", "strata.v1.RenderService.Stream"}, {"concurrency", o.concurrency},
                  {"total", o.total}, {"duration", ns(o.duration_s * 1000.0)}, {"rps", o.rps},
                  {"connections", o.connections}, {"timeout", ns(o.timeout_s * 1000.0)}, {"skipFirst", o.skip_first},
                  {"loadSchedule", o.schedule.kind}, {"loadStart", o.schedule.start}, {"loadStep", o.schedule.step},
                  {"loadEnd", o.schedule.end}, {"loadStepDuration", ns(o.schedule.step_duration_s * 1000.0)},
                  {"scene", o.scene}, {"method", o.method}, {"width", o.width}, {"height", o.height}, {"spp", o.spp},
                  {"encodings", o.encodings}, {"cameraPath", o.camera_path}};
  r["date"] = run.date;
  r["count"] = sent;
  r["total"] = ns(total_ms);
  r["average"] = sorted.empty() ? 0 : ns(sum / double(sorted.size()));
  r["fastest"] = sorted.empty() ? 0 : ns(sorted.front());
  r["slowest"] = sorted.empty() ? 0 : ns(sorted.back());
  r["rps"] = total_ms > 0.0 ? double(sent) / (total_ms / 1000.0) : 0.0;
  r["errorDistribution"] = errors;
  r["statusCodeDistribution"] = status_codes;
  json dist = json::array();
  for (double p : {10.0, 25.0, 50.0, 75.0, 90.0, 95.0, 99.0, 99.9})
    dist.push_back({{"percentage", p}, {"latency", ns(percentile(sorted, p))}});
  r["latencyDistribution"] = dist;
  r["histogram"] = histogram(sorted);
  if (o.details) r["details"] = details;

  json per_second = json::array();
  for (int sec = 0; sec < seconds; ++sec) {
    auto& v = per_second_latency[size_t(sec)];
    std::sort(v.begin(), v.end());
    per_second.push_back({{"second", sec}, {"inputs_sent", per_second_sent[size_t(sec)]},
                          {"frames_received", per_second_frames[size_t(sec)]}, {"latency_p50_ms", percentile(v, 50)},
                          {"latency_p99_ms", percentile(v, 99)}});
  }
  r["strata"] = {
      {"device", run.device},
      {"frames",
       {{"inputs_sent", sent}, {"frames_received", received}, {"answered_by_own_frame", own}, {"frames_dropped", dropped},
        {"inputs_coalesced", coalesced}, {"errors", unanswered}}},
      // The rate inputs actually went out at (the pacer's work: --rps when the client keeps up).
      {"sent_per_second", sent >= 2 && *last_sent > *first_sent ? double(sent - 1) / (ms_between(*first_sent, *last_sent) / 1000.0) : 0.0},
      {"frames_per_second", total_ms > 0.0 ? double(received) / (total_ms / 1000.0) : 0.0},
      {"latency_ms", stats_ms(latencies)},
      {"time_to_first_frame_ms", stats_ms(ttff_ms)},
      {"session_fps", stats_ms(fps)},
      {"inter_frame_gap_ms", stats_ms(gaps_ms)},
      {"server_gpu_ms", stats_ms(gpu_ms)},
      {"history_resets", resets},
      {"create_session_ms", stats_ms(create_ms)},
      {"delete_session_ms", stats_ms(delete_ms)},
      {"rpcStatusCodes", rpc_codes},
      {"per_session", per_session},
      {"per_second", per_second}};
  return r;
}

}  // namespace strata::client
