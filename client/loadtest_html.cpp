#include "loadtest_html.h"

#include <fstream>
#include <stdexcept>

#include "report/assets.h"
#include "report/util.h"

namespace strata::client {
namespace {

// Builds the three plots from the JSON block; sets data-plots on <body> and "[ready]" in the title
// once drawn (what a headless browser check waits for).
constexpr const char* k_script = R"JS(
(function () {
  const r = JSON.parse(document.getElementById('data').textContent);
  const s = r.strata;
  const width = Math.min(1100, document.body.clientWidth - 40);
  let plots = 0;
  function plot(id, title, data, series, opts) {
    const el = document.getElementById(id);
    new uPlot(Object.assign({ title: title, width: width, height: 260, series: [{}].concat(series),
      scales: { x: { time: false } } }, opts || {}), data, el);
    plots++;
  }
  const secs = s.per_second.map(p => p.second);
  plot('latency', 'Frame latency from scheduled send (ms) per second',
       [secs, s.per_second.map(p => p.latency_p50_ms), s.per_second.map(p => p.latency_p99_ms)],
       [{ label: 'p50', stroke: '#1f77b4', width: 2 }, { label: 'p99', stroke: '#d62728', width: 2 }],
       { axes: [{ label: 'second' }, { label: 'ms' }] });
  const h = r.histogram;
  plot('histogram', 'Latency histogram (count per bucket; x: bucket upper bound, ms)',
       [h.map(b => b.mark * 1000), h.map(b => b.count)],
       [{ label: 'frames', stroke: '#2ca02c', fill: 'rgba(44,160,44,0.3)', width: 2,
          paths: uPlot.paths.bars({ size: [0.9] }) }],
       { axes: [{ label: 'ms' }, { label: 'count' }] });
  const ps = s.per_session;
  plot('fps', 'Frames per second of each session',
       [ps.map(p => p.index), ps.map(p => p.fps)],
       [{ label: 'fps', stroke: '#9467bd', fill: 'rgba(148,103,189,0.3)', width: 2,
          paths: uPlot.paths.bars({ size: [0.6] }) }],
       { axes: [{ label: 'session' }, { label: 'frames/s' }] });
  document.body.setAttribute('data-plots', String(plots));
  document.title += ' [ready]';
})();
)JS";

constexpr const char* k_style = R"CSS(
body { font-family: sans-serif; margin: 20px; color: #222; }
table { border-collapse: collapse; margin: 12px 0; }
td, th { border: 1px solid #ccc; padding: 3px 8px; text-align: right; }
th { background: #f3f3f3; }
td:first-child, th:first-child { text-align: left; }
.plot { margin: 16px 0; }
)CSS";

std::string json_in_script(const nlohmann::json& j) {
  std::string text = j.dump(-1, ' ', false, nlohmann::json::error_handler_t::replace);
  std::string out;
  out.reserve(text.size());
  for (size_t i = 0; i < text.size(); ++i) {
    if (text[i] == '<' && i + 1 < text.size() && (text[i + 1] == '/' || text[i + 1] == '!')) out += "\\u003c";  // cannot close the element
    else out += text[i];
  }
  return out;
}

std::string row(const std::string& name, const std::string& value) {
  return "<tr><td>" + report::detail::html_escape(name) + "</td><td>" + report::detail::html_escape(value) + "</td></tr>\n";
}

std::string fmt(double v) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "%.2f", v);
  return buf;
}

}  // namespace

void write_loadtest_html(const nlohmann::json& r, const std::filesystem::path& path) {
  using report::detail::html_escape;
  const auto& s = r["strata"];
  const auto& f = s["frames"];
  const std::string title = r["name"].get<std::string>();
  std::string html = "<!DOCTYPE html>\n<html lang=\"en\">\n<head>\n<meta charset=\"utf-8\">\n<title>" + html_escape(title) +
                     "</title>\n<style>\n";
  html += report::assets::uplot_css();
  html += k_style;
  html += "</style>\n</head>\n<body>\n<h1>" + html_escape(title) + "</h1>\n<p>" + html_escape(r["date"].get<std::string>()) + " &middot; " +
          html_escape(r["options"]["host"].get<std::string>()) + " &middot; " + html_escape(s["device"].get<std::string>()) + "</p>\n";
  html += "<table>\n<tr><th>quantity</th><th>value</th></tr>\n";
  html += row("inputs sent (count)", std::to_string(f["inputs_sent"].get<uint64_t>()));
  html += row("frames received", std::to_string(f["frames_received"].get<uint64_t>()));
  html += row("frames dropped (server)", std::to_string(f["frames_dropped"].get<uint64_t>()));
  html += row("inputs coalesced (server)", std::to_string(f["inputs_coalesced"].get<uint64_t>()));
  html += row("errors (inputs unanswered)", std::to_string(f["errors"].get<uint64_t>()));
  html += row("frames/s (all sessions)", fmt(s["frames_per_second"].get<double>()));
  html += row("latency p50 / p99 (ms)", fmt(s["latency_ms"]["p50"].get<double>()) + " / " + fmt(s["latency_ms"]["p99"].get<double>()));
  html += row("time to first frame p50 (ms)", fmt(s["time_to_first_frame_ms"]["p50"].get<double>()));
  html += row("inter-frame gap p99 (ms)", fmt(s["inter_frame_gap_ms"]["p99"].get<double>()));
  html += row("server GPU ms mean", fmt(s["server_gpu_ms"]["mean"].get<double>()));
  html += row("history resets", std::to_string(s["history_resets"].get<uint64_t>()));
  html += row("CreateSession p50 (ms)", fmt(s["create_session_ms"]["p50"].get<double>()));
  html += row("DeleteSession p50 (ms)", fmt(s["delete_session_ms"]["p50"].get<double>()));
  html += row("status codes", r["statusCodeDistribution"].dump());
  html += row("RPC status codes", s["rpcStatusCodes"].dump());
  html += "</table>\n<div class=\"plot\" id=\"latency\"></div>\n<div class=\"plot\" id=\"histogram\"></div>\n"
          "<div class=\"plot\" id=\"fps\"></div>\n<footer>Plots: uPlot " +
          html_escape(report::assets::uplot_version()) + "</footer>\n";
  html += "<script type=\"application/json\" id=\"data\">" + json_in_script(r) + "</script>\n<script>\n";
  html += report::assets::uplot_js();
  html += "\n</script>\n<script>\n";
  html += k_script;
  html += "</script>\n</body>\n</html>\n";
  std::ofstream out(path, std::ios::binary);
  out << html;
  if (!out) throw std::runtime_error("cannot write " + path.string());
}

}  // namespace strata::client
