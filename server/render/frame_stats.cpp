#include "render/frame_stats.h"

#include <nlohmann/json.hpp>

namespace strata::render {

uint64_t FrameStats::rays_total() const {
  uint64_t n = 0;
  for (const auto& [kind, count] : rays_traced) n += count;
  return n;
}

nlohmann::json to_json(const FrameStats& s) {
  nlohmann::json j;
  j["frame"] = s.frame;
  nlohmann::json passes = nlohmann::json::object();
  for (const auto& p : s.pass_ms) passes[p.pass] = p.ms;
  j["pass_ms"] = passes;
  j["gpu_ms_total"] = s.gpu_ms_total;
  j["rays_traced"] = s.rays_traced;
  j["rays_total"] = s.rays_total();
  j["paths"] = s.paths;
  j["nonfinite_rejected"] = s.nonfinite_rejected;
  if (!s.reuse.empty()) j["reuse"] = s.reuse;
  if (!s.shift_failures.empty()) j["shift_failures"] = s.shift_failures;
  j["memory_bytes"] = s.memory_bytes;
  nlohmann::json decisions = nlohmann::json::array();
  for (const auto& d : s.passes) decisions.push_back({{"pass", d.pass}, {"ran", d.ran}, {"reason", d.reason}});
  j["passes"] = decisions;
  j["tlas"] = {{"builds", s.tlas_builds}, {"refits", s.tlas_refits}};
  return j;
}

}  // namespace strata::render
