#pragma once
// Internal to strata_report: the parts of report.html that are plain HTML, written in C++ so that
// they read without JavaScript (the plots and pass-cost bars are built by web/report.js).
#include <string>

#include "report/report.h"

namespace strata::report::detail {

// The meta object as a two-column table (strings unquoted, other values as JSON).
std::string meta_table_html(const nlohmann::json& meta);
// The equal-time summary: per scene and method, median ms, pt spp, mean errors and the
// method/pt ratios, a ratio below 1 marked "good" (the method wins) and above 1 "bad".
std::string summary_table_html(const Report& report);
// One scene's runs: method, spp, frames, median GPU ms and mean errors.
std::string runs_table_html(const Report& report, const std::string& scene);
// One scene's image insets as data: URIs (PNG bytes), error maps with their colour scale.
std::string insets_html(const Report& report, const std::string& scene);

}  // namespace strata::report::detail
