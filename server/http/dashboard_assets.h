#pragma once
// The dashboard's and the viewer's web assets, embedded at build time by cmake/embed_assets.cmake:
// uPlot from the npm package pinned in cmake/uplot/package-lock.json, and the pages' own scripts
// and styles from web/.
#include <string_view>

namespace strata::http::assets {

std::string_view uplot_js();
std::string_view uplot_css();
std::string_view uplot_version();
std::string_view dashboard_js();
std::string_view dashboard_css();
std::string_view view_js();
std::string_view view_css();

}  // namespace strata::http::assets
