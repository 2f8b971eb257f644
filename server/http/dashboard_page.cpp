#include <string>

#include "http/dashboard_assets.h"
#include "http/http_server.h"

namespace strata::http {

std::string dashboard_page() {
  std::string html =
      "<!DOCTYPE html>\n<html lang=\"en\">\n<head>\n<meta charset=\"utf-8\">\n<title>stratad dashboard</title>\n<link rel=\"icon\" href=\"data:,\">\n<style>\n";
  html += assets::uplot_css();
  html += assets::dashboard_css();
  html += "</style>\n</head>\n<body>\n<header><h1>stratad</h1><span id=\"status\">connecting</span>"
          "<form id=\"token-form\" style=\"display:none\"><input id=\"token\" type=\"password\" autocomplete=\"off\" "
          "placeholder=\"access token (--auth-token-file)\"><button>connect</button></form></header>\n"
          "<main id=\"sessions\"></main>\n<footer>Plots: uPlot ";
  html += assets::uplot_version();
  html += "</footer>\n<script>\n";
  html += assets::uplot_js();
  html += "\n</script>\n<script>\n";
  html += assets::dashboard_js();
  html += "\n</script>\n</body>\n</html>\n";
  return html;
}

}  // namespace strata::http
