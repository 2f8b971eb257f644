#include "loadtest_options.h"

#include <algorithm>
#include <cmath>
#include <map>
#include <sstream>
#include <stdexcept>

namespace strata::client {
namespace {

std::string num(double v) {
  std::ostringstream s;
  s << v;
  return s.str();
}

[[noreturn]] void bad(const std::string& what) { throw std::invalid_argument(what); }

}  // namespace

std::vector<v1::ImageEncoding> parse_encoding_list(const std::string& list) {
  static const std::map<std::string, v1::ImageEncoding> names = {
      {"exr", v1::IMAGE_ENCODING_EXR_HALF}, {"raw", v1::IMAGE_ENCODING_RAW_RGBA16F}, {"png", v1::IMAGE_ENCODING_PNG_PREVIEW},
      {"domain", v1::IMAGE_ENCODING_DOMAIN_MAP}};
  std::vector<v1::ImageEncoding> out;
  std::stringstream ss(list);
  for (std::string item; std::getline(ss, item, ',');) {
    auto it = names.find(item);
    if (it == names.end()) bad("--encodings: '" + item + "' is not one of exr, raw, png, domain");
    out.push_back(it->second);
  }
  if (out.empty()) bad("--encodings is empty");
  return out;
}

void LoadtestOptions::validate() const {
  if (concurrency < 1 || concurrency > k_max_concurrency)
    bad("-c/--concurrency = " + std::to_string(concurrency) + " must be in 1.." + std::to_string(k_max_concurrency));
  if (connections < 1 || connections > concurrency)
    bad("--connections = " + std::to_string(connections) + " must be in 1..concurrency (" + std::to_string(concurrency) + ")");
  if (total == 0 && duration_s <= 0.0) bad("give -n/--total (frames) or -z/--duration (seconds): the run must stop by itself");
  if (total > k_max_total) bad("-n/--total = " + std::to_string(total) + " is above the limit " + std::to_string(k_max_total));
  if (duration_s < 0.0 || duration_s > k_max_duration_s || !std::isfinite(duration_s))
    bad("-z/--duration = " + num(duration_s) + " s must be in 0.." + num(k_max_duration_s) + " s");
  if (rps < 0.0 || rps > k_max_rps || !std::isfinite(rps)) bad("--rps = " + num(rps) + " must be in 0.." + num(k_max_rps) + " frames/s");
  if (timeout_s <= 0.0 || timeout_s > k_max_timeout_s)
    bad("--timeout = " + num(timeout_s) + " s must be in (0, " + num(k_max_timeout_s) + "] s");
  if (width == 0 || height == 0) bad("--width and --height must be at least 1");
  if (spp == 0) bad("--spp must be at least 1");
  parse_encoding_list(encodings);
  const auto& s = schedule;
  if (s.kind == "const") return;
  if (s.kind != "step" && s.kind != "line") bad("--load-schedule = '" + s.kind + "' is not one of const, step, line");
  if (rps > 0.0) bad("--rps is for --load-schedule const; " + s.kind + " takes --load-start, --load-step and --load-end");
  if (s.start <= 0.0 || s.start > k_max_rps) bad("--load-start = " + num(s.start) + " must be in (0, " + num(k_max_rps) + "] frames/s");
  if (s.end < 0.0 || s.end > k_max_rps) bad("--load-end = " + num(s.end) + " must be in 0.." + num(k_max_rps) + " frames/s (0: no end)");
  if (!std::isfinite(s.step) || std::abs(s.step) > k_max_rps) bad("--load-step = " + num(s.step) + " must be within +-" + num(k_max_rps));
  if (s.kind == "step" && (s.step_duration_s <= 0.0 || s.step_duration_s > k_max_duration_s))
    bad("--load-step-duration = " + num(s.step_duration_s) + " s must be in (0, " + num(k_max_duration_s) + "] s");
}

double LoadtestOptions::rate_at(double t) const {
  const auto& s = schedule;
  double r = rps;
  if (s.kind == "step") r = s.start + s.step * std::floor(t / s.step_duration_s);
  else if (s.kind == "line") r = s.start + s.step * t;
  if (s.kind != "const" && s.end > 0.0) r = s.step >= 0.0 ? std::min(r, s.end) : std::max(r, s.end);
  // A falling schedule never pauses the run entirely: at least one frame every 10 s.
  return std::max(r, 0.1);
}

}  // namespace strata::client
