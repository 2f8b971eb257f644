// The plain-HTML parts of report.html (see html_sections.h).
#include "report/html_sections.h"

#include <algorithm>
#include <cmath>
#include <string_view>
#include <vector>

#include "report/colormap.h"
#include "report/util.h"

namespace strata::report::detail {
namespace {

double median(std::vector<double> values) {
  if (values.empty()) return std::nan("");
  std::sort(values.begin(), values.end());
  const size_t n = values.size();
  return n % 2 == 1 ? values[n / 2] : 0.5 * (values[n / 2 - 1] + values[n / 2]);
}

std::string td(const std::string& text, std::string_view cls = {}) {
  if (cls.empty()) return "<td>" + text + "</td>";
  return "<td class=\"" + std::string(cls) + "\">" + text + "</td>";
}

std::string num_td(double value) { return td(format_short(value), "num"); }

std::string ratio_td(double ratio) {
  std::string_view cls = "num";
  if (std::isfinite(ratio) && ratio < 1.0) cls = "num good";
  if (std::isfinite(ratio) && ratio > 1.0) cls = "num bad";
  return td(format_short(ratio), cls);
}

// A CSS gradient through the magma colour map, for the error maps' colour scale.
std::string magma_gradient() {
  std::string css = "linear-gradient(to right";
  for (int i = 0; i <= 8; ++i) {
    const auto c = magma(float(i) / 8.0f);
    css += ", rgb(" + std::to_string(c[0]) + "," + std::to_string(c[1]) + "," + std::to_string(c[2]) + ")";
  }
  return css + ")";
}

}  // namespace

std::string meta_table_html(const nlohmann::json& meta) {
  if (!meta.is_object() || meta.empty()) return {};
  std::string out = "<table class=\"meta\">\n";
  for (const auto& [key, value] : meta.items()) {
    const std::string text = value.is_string()
                                 ? value.get<std::string>()
                                 : value.dump(-1, ' ', false, nlohmann::json::error_handler_t::replace);
    out += "<tr><th>" + html_escape(key) + "</th><td>" + html_escape(text) + "</td></tr>\n";
  }
  return out + "</table>\n";
}

std::string summary_table_html(const Report& report) {
  if (report.equal_time.empty()) return "<p class=\"empty\">No equal-time comparisons.</p>\n";
  std::string out =
      "<table class=\"summary\">\n<thead><tr><th rowspan=\"2\">scene</th><th rowspan=\"2\">method</th>"
      "<th rowspan=\"2\">median ms</th><th rowspan=\"2\">pt spp</th><th rowspan=\"2\">pt median ms</th>"
      "<th colspan=\"3\">RelMSE</th><th colspan=\"3\">MAPE</th><th colspan=\"3\">FLIP</th></tr>\n<tr>";
  for (int i = 0; i < 3; ++i) out += "<th>method</th><th>pt</th><th>ratio</th>";
  out += "</tr></thead>\n<tbody>\n";
  for (const std::string& scene : scene_order(report)) {
    for (const EqualTime& et : report.equal_time) {
      if (et.scene != scene) continue;
      out += "<tr>" + td(html_escape(et.scene)) + td(html_escape(et.method)) + num_td(et.method_median_ms) +
             td(std::to_string(et.pt_spp), "num") + num_td(et.pt_median_ms);
      out += num_td(et.method_mean.relmse) + num_td(et.pt_mean.relmse) + ratio_td(et.ratio.relmse);
      out += num_td(et.method_mean.mape) + num_td(et.pt_mean.mape) + ratio_td(et.ratio.mape);
      out += num_td(et.method_mean.flip) + num_td(et.pt_mean.flip) + ratio_td(et.ratio.flip);
      out += "</tr>\n";
    }
  }
  return out + "</tbody>\n</table>\n<p class=\"note\">ratio = method / pt at equal time: "
               "<span class=\"good\">below 1</span> the method wins, <span class=\"bad\">above 1</span> "
               "pt wins.</p>\n";
}

std::string runs_table_html(const Report& report, const std::string& scene) {
  std::string out =
      "<table class=\"runs\">\n<thead><tr><th>method</th><th>spp</th><th>equal-time pt for</th>"
      "<th>frames</th><th>median GPU ms</th><th>mean RelMSE</th><th>mean MAPE</th><th>mean FLIP</th>"
      "</tr></thead>\n<tbody>\n";
  for (const Run& run : report.runs) {
    if (run.scene != scene) continue;
    std::vector<double> gpu_ms;
    Errors mean;
    for (const FrameResult& f : run.frames) {
      gpu_ms.push_back(f.gpu_ms);
      mean.relmse += f.whole.relmse;
      mean.mape += f.whole.mape;
      mean.flip += f.whole.flip;
    }
    const double n = run.frames.empty() ? std::nan("") : double(run.frames.size());
    out += "<tr>" + td(html_escape(run.method)) + td(std::to_string(run.spp), "num") +
           td(run.equal_time_pt ? html_escape(run.matched_method) : "") +
           td(std::to_string(run.frames.size()), "num") + num_td(median(gpu_ms)) + num_td(mean.relmse / n) +
           num_td(mean.mape / n) + num_td(mean.flip / n) + "</tr>\n";
  }
  return out + "</tbody>\n</table>\n";
}

std::string insets_html(const Report& report, const std::string& scene) {
  std::string out;
  for (const Insets& insets : report.insets) {
    if (insets.scene != scene || insets.images.empty()) continue;
    out += "<div class=\"insets\">\n<h4>Frame " + std::to_string(insets.frame) + "</h4>\n<div class=\"inset-row\">\n";
    bool any_error_map = false;
    for (const auto& [name, png] : insets.images) {
      const bool error_map = name.rfind("error:", 0) == 0;
      any_error_map = any_error_map || error_map;
      out += std::string("<figure") + (error_map ? " class=\"error-map\"" : "") + "><img alt=\"" +
             html_escape(name) + "\" src=\"data:image/png;base64," + base64(png) + "\"><figcaption>" +
             html_escape(name) + "</figcaption></figure>\n";
    }
    out += "</div>\n";
    if (any_error_map) {
      out += "<div class=\"colour-scale\"><span>0</span><span class=\"ramp\" style=\"background: " +
             magma_gradient() + "\"></span><span>max</span> error maps: magma, no tone mapping</div>\n";
    }
    out += "</div>\n";
  }
  return out;
}

}  // namespace strata::report::detail
