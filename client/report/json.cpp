// results.json (see report.h): meta, runs with their frames, equal-time entries and the names of
// the inset images (the images themselves go into report.html only).
#include "report/report.h"
#include "report/util.h"

namespace strata::report {
namespace {

nlohmann::json errors_json(const Errors& e) {
  return {{"relmse", e.relmse}, {"mape", e.mape}, {"flip", e.flip}, {"relmse_luminance", e.relmse_luminance}};
}

nlohmann::json frame_json(const FrameResult& f) {
  nlohmann::json j = {{"frame", f.frame},
                      {"gpu_ms", f.gpu_ms},
                      {"cumulative_ms", f.cumulative_ms},
                      {"pass_ms", nlohmann::json::object()},
                      {"whole", errors_json(f.whole)},
                      {"has_masked", f.has_masked},
                      {"masked_pixels", f.masked_pixels},
                      {"masked", nullptr}};
  for (const auto& [pass, ms] : f.pass_ms) j["pass_ms"][pass] = ms;
  if (f.has_masked) j["masked"] = errors_json(f.masked);
  return j;
}

nlohmann::json run_json(const Run& run) {
  nlohmann::json frames = nlohmann::json::array();
  for (const FrameResult& f : run.frames) frames.push_back(frame_json(f));
  return {{"scene", run.scene},
          {"method", run.method},
          {"spp", run.spp},
          {"equal_time_pt", run.equal_time_pt},
          {"matched_method", run.matched_method},
          {"round_ms", run.round_ms},
          {"round_pass_ms", run.round_pass_ms},
          {"round_choices", run.round_choices},
          {"choice_reason", run.choice_reason},
          {"frames", std::move(frames)}};
}

nlohmann::json equal_time_json(const EqualTime& et) {
  return {{"scene", et.scene},
          {"method", et.method},
          {"method_median_ms", et.method_median_ms},
          {"pt_median_ms", et.pt_median_ms},
          {"pt_spp", et.pt_spp},
          {"method_mean", errors_json(et.method_mean)},
          {"pt_mean", errors_json(et.pt_mean)},
          {"ratio", errors_json(et.ratio)},
          {"relmse_ratio_at_equal_ms", et.relmse_ratio_at_equal_ms}};
}

nlohmann::json insets_json(const Insets& insets) {
  nlohmann::json names = nlohmann::json::array();
  for (const auto& image : insets.images) names.push_back(image.first);
  return {{"scene", insets.scene}, {"frame", insets.frame}, {"images", std::move(names)}};
}

}  // namespace

nlohmann::json to_json(const Report& report) {
  nlohmann::json j;
  j["meta"] = report.meta.is_null() ? nlohmann::json::object() : report.meta;
  j["runs"] = nlohmann::json::array();
  for (const Run& run : report.runs) j["runs"].push_back(run_json(run));
  j["equal_time"] = nlohmann::json::array();
  for (const EqualTime& et : report.equal_time) j["equal_time"].push_back(equal_time_json(et));
  j["insets"] = nlohmann::json::array();
  for (const Insets& insets : report.insets) j["insets"].push_back(insets_json(insets));
  return j;
}

void write_json(const Report& report, const std::filesystem::path& path) {
  // Invalid UTF-8 in meta (a command line, say) is replaced rather than failing the whole report.
  const std::string text =
      to_json(report).dump(2, ' ', false, nlohmann::json::error_handler_t::replace) + "\n";
  detail::write_text_file(path, text, "write_json");
}

}  // namespace strata::report
