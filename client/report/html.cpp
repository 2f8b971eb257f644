// report.html: one self-contained page (see report.h). The uPlot library, the page's script and
// style are inlined from the assets embedded at build time; the data travels as a JSON block that
// web/report.js reads; images are data: URIs. Nothing is fetched when the page is opened.
#include <string>
#include <string_view>

#include "report/assets.h"
#include "report/html_sections.h"
#include "report/report.h"
#include "report/util.h"

namespace strata::report {
namespace {

void replace_all(std::string& text, std::string_view from, std::string_view to) {
  for (size_t pos = text.find(from); pos != std::string::npos; pos = text.find(from, pos + to.size())) {
    text.replace(pos, from.size(), to);
  }
}

// The data block's JSON, safe inside <script>: "</" (which could close the element) becomes
// "<\/", and "<!--" (which could start an escaped state) "\u003c!--". Both can only occur inside
// JSON strings, where these escapes read back to the same text.
std::string data_block_json(const Report& report) {
  nlohmann::json data = to_json(report);
  data["scenes"] = detail::scene_order(report);
  data["uplot_version"] = std::string(assets::uplot_version());
  std::string text = data.dump(-1, ' ', false, nlohmann::json::error_handler_t::replace);
  replace_all(text, "<!--", "\\u003c!--");
  replace_all(text, "</", "<\\/");
  return text;
}

std::string page_title(const Report& report) {
  const auto scenes = detail::scene_order(report);
  std::string title = "strata eval report";
  if (!scenes.empty()) {
    title += ":";
    for (const std::string& scene : scenes) title += " " + scene;
  }
  return title;
}

}  // namespace

std::string_view uplot_version() { return assets::uplot_version(); }

std::string to_html(const Report& report) {
  using namespace detail;
  const std::string title = page_title(report);
  std::string html;
  html.reserve(128 * 1024);
  html += "<!DOCTYPE html>\n<html lang=\"en\">\n<head>\n<meta charset=\"utf-8\">\n";
  html += "<meta name=\"viewport\" content=\"width=device-width, initial-scale=1\">\n";
  html += "<title>" + html_escape(title) + "</title>\n";
  html += "<style>\n";
  html += assets::uplot_css();
  html += "\n</style>\n<style>\n";
  html += assets::report_css();
  html += "\n</style>\n</head>\n<body>\n<header>\n<h1>" + html_escape(title) + "</h1>\n";
  html += meta_table_html(report.meta);
  html += "</header>\n<nav>";
  const auto scenes = scene_order(report);
  for (size_t i = 0; i < scenes.size(); ++i) {
    html += "<a href=\"#scene-" + std::to_string(i) + "\">" + html_escape(scenes[i]) + "</a>";
  }
  html += "</nav>\n<section id=\"summary\">\n<h2>Equal time</h2>\n" + summary_table_html(report) + "</section>\n";
  for (size_t i = 0; i < scenes.size(); ++i) {
    html += "<section class=\"scene\" id=\"scene-" + std::to_string(i) + "\" data-scene=\"" +
            html_escape(scenes[i]) + "\">\n<h2>" + html_escape(scenes[i]) + "</h2>\n";
    html += runs_table_html(report, scenes[i]);
    html += "<div class=\"plots-host\"></div>\n";
    html += "<h3>Per-pass GPU cost (median ms per frame)</h3>\n<div class=\"passes-host\"></div>\n";
    const std::string insets = insets_html(report, scenes[i]);
    if (!insets.empty()) html += "<h3>Images</h3>\n" + insets;
    html += "</section>\n";
  }
  html += "<footer>Plots: uPlot " + html_escape(assets::uplot_version()) +
          " (MIT), inlined; this page loads nothing from the network.</footer>\n";
  html += "<script type=\"application/json\" id=\"data\">" + data_block_json(report) + "</script>\n";
  html += "<script>\n";
  html += assets::uplot_js();
  html += "\n</script>\n<script>\n";
  html += assets::report_js();
  html += "\n</script>\n</body>\n</html>\n";
  return html;
}

void write_html(const Report& report, const std::filesystem::path& path) {
  detail::write_text_file(path, to_html(report), "write_html");
}

}  // namespace strata::report
