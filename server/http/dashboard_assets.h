#pragma once
// The dashboard's web assets, embedded at build time by cmake/embed_assets.cmake: uPlot from the npm
// package pinned in cmake/uplot/package-lock.json, and the page's own script and style from web/.
#include <string_view>

namespace strata::http::assets {

std::string_view uplot_js();
std::string_view uplot_css();
std::string_view uplot_version();
std::string_view dashboard_js();
std::string_view dashboard_css();

}  // namespace strata::http::assets
