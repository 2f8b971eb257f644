#include <string>

#include "http/dashboard_assets.h"
#include "http/http_server.h"

namespace strata::http {

std::string viewer_page() {
  std::string html =
      "<!DOCTYPE html>\n<html lang=\"en\">\n<head>\n<meta charset=\"utf-8\">\n<title>stratad viewer</title>\n"
      "<link rel=\"icon\" href=\"data:,\">\n<style>\n";
  html += assets::uplot_css();
  html += assets::view_css();
  html += R"(</style>
</head>
<body>
<header><h1>stratad viewer</h1><span id="status">connecting</span></header>
<div id="layout">
<div id="stage"><canvas id="frame" width="256" height="256" tabindex="0"></canvas><div id="hud"></div><div id="message"></div></div>
<aside>
<form id="token-form"><h2>Access token</h2><label>token <input id="token" type="password" autocomplete="off"></label><button type="submit">Connect</button></form>
<h2>Session</h2>
<label>scene <select id="scene"></select></label>
<label>method <select id="method"></select></label>
<label>width <input id="width" type="number" min="8" max="8192" value="256"></label>
<label>height <input id="height" type="number" min="8" max="8192" value="256"></label>
<button id="start" type="button">Start</button>
<label>render continuously <input id="run" type="checkbox" checked></label>
<h2>Options</h2>
<div id="options"></div>
<div id="overlay-box"><h2>Overlay</h2>
<label>domain map <input id="overlay" type="checkbox"></label>
<div id="overlay-legend">red: active domains (brighter = more), green: front layer disoccluded, blue: covered by a splat</div></div>
<h2>Selection</h2>
<div id="selection">none (click an object)</div>
<h2>Camera</h2>
<label>speed (units/s) <input id="speed" type="number" min="0.001" step="0.1" value="1"></label>
<div id="help">W A S D: move, Q E: down, up, Shift: faster; drag: look; click an object to select it, drag it to move it; [ ]: its LoD level</div>
<h2>Timing</h2>
<div id="chart"></div>
<h2>Decisions</h2>
<div id="decisions"></div>
</aside>
</div>
<footer style="display:none">Plots: uPlot )";
  html += assets::uplot_version();
  html += "</footer>\n<script>\n";
  html += assets::uplot_js();
  html += "\n</script>\n<script>\n";
  html += assets::view_js();
  html += "\n</script>\n</body>\n</html>\n";
  return html;
}

}  // namespace strata::http
