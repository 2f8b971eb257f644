#pragma once
// Internal to strata_report: the web assets inlined into report.html, embedded at build time by
// cmake/embed_assets.cmake (uPlot from the npm package pinned in cmake/uplot/package-lock.json, and the page's
// own script and style from web/).
#include <string_view>

namespace strata::report::assets {

std::string_view uplot_js();       // uPlot's dist/uPlot.iife.min.js (defines the global uPlot)
std::string_view uplot_css();      // uPlot's dist/uPlot.min.css
std::string_view uplot_version();  // the version field of uPlot's package.json
std::string_view report_js();      // web/report.js: builds the plots from the data block
std::string_view report_css();     // web/report.css

}  // namespace strata::report::assets
