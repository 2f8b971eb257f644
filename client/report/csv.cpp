// results.csv: one row per scene, run and frame (see report.h).
#include <string>
#include <string_view>

#include "report/report.h"
#include "report/util.h"

namespace strata::report {
namespace {

constexpr std::string_view kHeader =
    "scene,method,spp,equal_time_pt,frame,gpu_ms,cumulative_ms,relmse,mape,flip,"
    "masked_pixels,masked_relmse,masked_mape,masked_flip,relmse_luminance,masked_relmse_luminance";

// RFC 4180: a field with a comma, a quote, CR or LF (or edge spaces, which readers may trim) is
// quoted, and its quotes doubled.
std::string csv_field(std::string_view text) {
  const bool edge_space = !text.empty() && (text.front() == ' ' || text.back() == ' ');
  if (!edge_space && text.find_first_of(",\"\r\n") == std::string_view::npos) return std::string(text);
  std::string out = "\"";
  for (const char c : text) {
    if (c == '"') out += '"';
    out += c;
  }
  out += '"';
  return out;
}

void append_row(std::string& out, const Run& run, const FrameResult& f) {
  using detail::format_number;
  out += csv_field(run.scene);
  out += ',';
  out += csv_field(run.method);
  out += ',';
  out += std::to_string(run.spp);
  out += run.equal_time_pt ? ",true," : ",false,";
  out += std::to_string(f.frame);
  for (const double v : {f.gpu_ms, f.cumulative_ms, f.whole.relmse, f.whole.mape, f.whole.flip}) {
    out += ',';
    out += format_number(v);
  }
  out += ',';
  if (f.has_masked) {
    out += std::to_string(f.masked_pixels);
    for (const double v : {f.masked.relmse, f.masked.mape, f.masked.flip}) {
      out += ',';
      out += format_number(v);
    }
  } else {
    out += ",,,";
  }
  out += ',';
  out += format_number(f.whole.relmse_luminance);
  out += ',';
  if (f.has_masked) out += format_number(f.masked.relmse_luminance);
  out += "\n";
}

}  // namespace

std::string to_csv(const Report& report) {
  std::string out(kHeader);
  out += "\n";
  for (const std::string& scene : detail::scene_order(report)) {
    for (const Run& run : report.runs) {
      if (run.scene != scene) continue;
      for (const FrameResult& f : run.frames) append_row(out, run, f);
    }
  }
  return out;
}

void write_csv(const Report& report, const std::filesystem::path& path) {
  detail::write_text_file(path, to_csv(report), "write_csv");
}

}  // namespace strata::report
