#include "render/method_table.h"

#include <stdexcept>

namespace strata::render {

const std::vector<MethodSpec>& method_table() {
  using S = StageKind;
  static const std::vector<MethodSpec> table = {
      // name, summary, reuse, direct_lighting, splatting, backup, layers, temporal, fixed_primary, confidence_cap,
      // disocclusion_initial_candidates
      {"pt", "reference path tracer: next-event estimation and MIS, no reuse", false, false, false, false, false, S::path_trace,
       false, 4.0f, 0},
      {"restir-gather", "ReSTIR PT (GRIS): gather temporal reuse by backprojection, spatial reuse", true, false, false, false, false,
       S::temporal_gather, true, 2.0f, 0},
      {"restir-di", "ReSTIR DI: resampled direct lighting over one-bounce paths (camera, first hit, light)", true, true, false,
       false, false, S::temporal_gather, true, 4.0f, 0},
      {"restir-splat", "reservoir splatting: previous reservoirs forward-projected with their primary hits (RS-main 4.1)", true,
       false, true, false, false, S::temporal_splat, false, 2.0f, 0},
      {"restir-splat-backup", "reservoir splatting with the backprojected backup sample (RS-main 4.2)", true, false, true, true,
       false, S::temporal_splat, false, 2.0f, 0},
      {"restir-multilayer",
       "multi-layer reservoir splatting: pixel-layer domains with depth ranges, active domains kept through disocclusions (ML)", true,
       false, true, false, true, S::temporal_splat, false, 2.0f, 8},
  };
  return table;
}

const MethodSpec& method_spec(const std::string& name, const std::string& field) {
  for (const auto& m : method_table())
    if (name == m.name) return m;
  throw std::invalid_argument(field + " = '" + name + "' is not a method; methods: " + method_names());
}

std::vector<std::string> available_methods() {
  std::vector<std::string> names;
  for (const auto& m : method_table()) names.emplace_back(m.name);
  return names;
}

std::string method_names() {
  std::string s;
  for (const auto& m : method_table()) s += (s.empty() ? "" : ", ") + std::string(m.name);
  return s;
}

std::string method_help() {
  std::string s;
  for (const auto& m : method_table()) s += std::string("\n  ") + m.name + ": " + m.summary;
  return s;
}

}  // namespace strata::render
