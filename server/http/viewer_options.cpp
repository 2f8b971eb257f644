#include "http/viewer_options.h"

#include <algorithm>
#include <stdexcept>

#include "options/option_table.h"

namespace strata::http {
namespace {

struct PanelRow {
  const char* field;   // an option table row (RenderOptions field)
  const char* label;
  double slider_max;   // the slider's end where the table's range is far wider than a panel needs (0: the table's)
  double step;
};

// The panel's rows, in the order it shows them.
constexpr PanelRow k_panel[] = {
    {"spp", "samples per pixel", 16, 1},
    {"max_depth", "path segments", 16, 1},
    {"exposure", "exposure (stops)", 6, 0.25},
    {"initial_candidates", "initial candidates", 16, 1},
    {"spatial_neighbors", "spatial neighbours", 0, 1},
    {"confidence_cap", "confidence cap", 64, 1},
    {"temporal_reuse", "temporal reuse", 0, 1},
    {"spatial_reuse", "spatial reuse", 0, 1},
};

}  // namespace

nlohmann::json viewer_options_json() {
  nlohmann::json out = nlohmann::json::array();
  for (const PanelRow& row : k_panel) {
    const options::OptionSpec* o = options::find_option(row.field);
    if (!o || o->group != options::Group::user)
      throw std::logic_error(std::string("viewer option '") + row.field + "' is not a user option of the option table");
    std::string kind;
    switch (o->kind) {
      case options::Kind::count: kind = "uint"; break;
      case options::Kind::real: kind = "float"; break;
      case options::Kind::flag: kind = "bool"; break;
      case options::Kind::choice: throw std::logic_error(std::string("viewer option '") + row.field + "' is a choice: the panel has no control for it");
    }
    // A row whose upper end is a service limit (hi 0) takes the panel's; the symmetric exposure range keeps its shape.
    double hi = o->hi > 0 ? o->hi : row.slider_max;
    if (row.slider_max > 0) hi = std::min(hi, row.slider_max);
    const double lo = o->lo < 0 ? -hi : o->lo;
    out.push_back({{"field", row.field}, {"label", row.label}, {"kind", kind}, {"min", lo}, {"max", hi}, {"step", row.step},
                   {"restir_only", o->scope != options::Scope::every}});
  }
  return out;
}

}  // namespace strata::http
