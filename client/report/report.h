#pragma once
// The evaluation report of `strata eval`: results.csv, results.json and a self-contained
// report.html (plots with uPlot inlined at build time, images as data URIs; no network access).
#include <cstdint>
#include <filesystem>
#include <map>
#include <stdexcept>
#include <string>
#include <string_view>
#include <vector>

#include <nlohmann/json.hpp>

namespace strata::report {

// Error of one image against the reference, over all pixels and over the disoccluded ones.
struct Errors {
  double relmse = 0.0, mape = 0.0, flip = 0.0;
  double relmse_luminance = 0.0;  // RelMSE of the luminance alone (metrics::relmse_luminance)
};

struct FrameResult {
  uint32_t frame = 0;
  double gpu_ms = 0.0;                       // the frame's GPU time (sum of its passes)
  double cumulative_ms = 0.0;                // GPU time of this run up to and including the frame
  std::map<std::string, double> pass_ms;     // per-pass GPU time
  Errors whole;
  bool has_masked = false;                   // false when the frame has no disoccluded pixels
  Errors masked;
  uint64_t masked_pixels = 0;
};

struct Run {
  std::string scene, method;
  uint32_t spp = 1;
  bool equal_time_pt = false;                // pt given the time of `matched_method`
  std::string matched_method;
  std::vector<FrameResult> frames;
  // With --timing-rounds R > 1: the median frame time of each of the R runs of this method (the
  // first is `frames`'s own; the errors are the same every round, the ms are not). The run's time
  // is their median (median_gpu_ms).
  std::vector<double> round_ms;
  // The same per pass: each round's median ms of every pass (the first round's from `frames`).
  std::vector<std::map<std::string, double>> round_pass_ms;
  // Method auto: the method it chose in each round (the first is `frames`'s), and the scored
  // round's reason. Its choice rests on measured time, so rounds may choose differently; the
  // run's time then mixes the choices' times (print_summary says so).
  std::vector<std::string> round_choices;
  std::string choice_reason;
};

// Equal-time comparison: pt with `pt_spp` samples per frame against a method's median frame time.
struct EqualTime {
  std::string scene, method;
  double method_median_ms = 0.0, pt_median_ms = 0.0;
  uint32_t pt_spp = 1;
  Errors method_mean, pt_mean;               // mean over frames (whole image)
  Errors ratio;                              // method / pt: < 1 means the method wins
  // The RelMSE ratio with pt's error moved to exactly the method's time (RelMSE x time is constant
  // for pt, whose spp are independent): ratio.relmse x method ms / pt ms. The whole spp that fit in
  // the method's time make `ratio` jump with timing noise; this one does not.
  double relmse_ratio_at_equal_ms = 0.0;
};

// PNG images (8-bit sRGB, already encoded) shown side by side for one frame of one scene:
// "reference", each method name, and "error:<method>" for its error map.
struct Insets {
  std::string scene;
  uint32_t frame = 0;
  std::vector<std::pair<std::string, std::vector<uint8_t>>> images;
};

struct Report {
  nlohmann::json meta;                       // server, device, date, resolution, frames, command line
  std::vector<Run> runs;
  std::vector<EqualTime> equal_time;
  std::vector<Insets> insets;
};

// Thrown when a report file cannot be written, or an error map gets bad arguments.
struct ReportError : std::runtime_error {
  using std::runtime_error::runtime_error;
};

// results.csv: a header, then one row per run and frame (runs grouped by scene, in the order the
// scenes first appear). The masked_* cells are empty where has_masked is false. Numbers are written
// in their shortest round-trip form; text cells are quoted as RFC 4180 says when they need it.
std::string to_csv(const Report& report);
void write_csv(const Report& report, const std::filesystem::path& path);
nlohmann::json to_json(const Report& report);   // results.json (images not included)
void write_json(const Report& report, const std::filesystem::path& path);
// report.html as one self-contained page: uPlot (inlined at build time), the page's script and
// style, the data (to_json plus the scene list) in <script type="application/json" id="data">
// with "</" escaped as "<\/", and the insets as data: URIs. Opening it needs no network access.
// When every plot is drawn, the page sets <body data-plots="N" data-plot-rects="[[x,y,w,h],...]">
// (the plot areas in CSS pixels, for tests) and a title ending in "[ready]"; it logs nothing.
std::string to_html(const Report& report);
void write_html(const Report& report, const std::filesystem::path& path);
// The uPlot version inlined into report.html (from the npm package at build time).
std::string_view uplot_version();

// An error map (values >= 0, width*height) as an 8-bit PNG with a perceptual colour map
// (values/max_value clamped to [0, 1]).
// The colour map is matplotlib's magma (17 samples, linearly interpolated): 0 is near black
// (0, 0, 4), 1 is pale yellow (252, 253, 191); NaN and +inf map to 1. No tone mapping. Throws
// ReportError when values.size() != width*height, the size is zero, or max_value is not > 0.
std::vector<uint8_t> error_map_png(const std::vector<float>& values, uint32_t width, uint32_t height,
                                   float max_value = 1.0f);

}  // namespace strata::report
