#include "http/viewer_options.h"

#include <stdexcept>

#include "strata/v1/render.pb.h"

namespace strata::http {

const std::vector<ViewerOption>& viewer_options() {
  static const std::vector<ViewerOption> options = {
      {"spp", "samples per pixel", 1, 16, 1, false},
      {"max_depth", "path segments", 1, 16, 1, false},
      {"exposure", "exposure (stops)", -6, 6, 0.25, false},
      {"initial_candidates", "initial candidates", 1, 16, 1, true},
      {"spatial_neighbors", "spatial neighbours", 0, 8, 1, true},
      {"confidence_cap", "confidence cap", 1, 64, 1, true},
      {"temporal_reuse", "temporal reuse", 0, 1, 1, true},
      {"spatial_reuse", "spatial reuse", 0, 1, 1, true},
  };
  return options;
}

nlohmann::json viewer_options_json() {
  const auto* descriptor = v1::RenderOptions::descriptor();
  nlohmann::json out = nlohmann::json::array();
  for (const auto& o : viewer_options()) {
    const auto* f = descriptor->FindFieldByName(o.field);
    if (!f) throw std::logic_error(std::string("viewer option '") + o.field + "' is not a field of strata.v1.RenderOptions");
    std::string kind;
    switch (f->cpp_type()) {
      case google::protobuf::FieldDescriptor::CPPTYPE_UINT32: kind = "uint"; break;
      case google::protobuf::FieldDescriptor::CPPTYPE_FLOAT: kind = "float"; break;
      case google::protobuf::FieldDescriptor::CPPTYPE_BOOL: kind = "bool"; break;
      default: throw std::logic_error(std::string("viewer option '") + o.field + "' has a type the panel cannot show");
    }
    out.push_back({{"field", o.field}, {"label", o.label}, {"kind", kind}, {"min", o.min}, {"max", o.max},
                   {"step", o.step}, {"restir_only", o.restir_only}});
  }
  return out;
}

}  // namespace strata::http
