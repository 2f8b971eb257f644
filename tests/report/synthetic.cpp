// The synthetic report of the report tests (see synthetic.h).
#include "synthetic.h"

#include <cmath>
#include <string>
#include <vector>

#include "image/image.h"

namespace strata::report::testing {
namespace {

std::vector<uint8_t> gradient_png(uint32_t width, uint32_t height, float noise) {
  image::Image img{width, height, std::vector<float>(4 * size_t(width) * height)};
  for (uint32_t y = 0; y < height; ++y) {
    for (uint32_t x = 0; x < width; ++x) {
      float* p = img.pixel(x, y);
      const float n = noise * float((x * 7919u + y * 104729u) % 97u) / 97.0f;
      p[0] = float(x) / float(width) + n;
      p[1] = float(y) / float(height) + n;
      p[2] = 0.3f + n;
      p[3] = 1.0f;
    }
  }
  return image::encode_png_preview(img);
}

std::vector<uint8_t> error_png(uint32_t width, uint32_t height, float scale) {
  std::vector<float> values(size_t(width) * height);
  for (uint32_t y = 0; y < height; ++y) {
    for (uint32_t x = 0; x < width; ++x) values[size_t(y) * width + x] = scale * float(x + y) / float(width + height);
  }
  return error_map_png(values, width, height, 1.0f);
}

Run make_run(const std::string& scene, const std::string& method, uint32_t spp, bool equal_time,
             double error_scale, double ms_scale, const SyntheticOptions& options) {
  Run run{scene, method, spp, equal_time, equal_time ? "restir-gather" : "", {}};
  double cumulative = 0.0;
  for (uint32_t i = 0; i < options.frames; ++i) {
    FrameResult f;
    f.frame = i;
    const double wobble = 1.0 + 0.1 * std::sin(double(i));
    f.pass_ms = {{"trace", 2.0 * ms_scale * wobble}, {"shade", 1.0 * ms_scale}, {"tonemap", 0.25}};
    if (method != "pt") f.pass_ms["temporal"] = 0.75 * ms_scale;
    for (const auto& [pass, ms] : f.pass_ms) f.gpu_ms += ms;
    cumulative += f.gpu_ms;
    f.cumulative_ms = cumulative;
    const double decay = error_scale / std::sqrt(1.0 + double(i));
    f.whole = {0.5 * decay, 0.2 * decay, 0.1 * decay};
    f.has_masked = options.masked && i > 0;
    if (f.has_masked) {
      f.masked = {1.5 * decay, 0.6 * decay, 0.3 * decay};
      f.masked_pixels = 100 + 10 * i;
    }
    run.frames.push_back(f);
  }
  return run;
}

}  // namespace

Report synthetic_report(const SyntheticOptions& options) {
  Report report;
  report.meta = {{"server", "stratad 0.1.0"},
                 {"device", "llvmpipe (synthetic)"},
                 {"date", "2025-01-01T00:00:00Z"},
                 {"resolution", {64, 48}},
                 {"frames", options.frames},
                 {"command_line", "strata eval --note '</script><script>alert(1)</script>'"}};
  for (uint32_t s = 0; s < options.scenes; ++s) {
    const std::string scene = s == 0 ? "cornell" : s == 1 ? "chess" : "scene-" + std::to_string(s);
    const double k = 1.0 + double(s);
    report.runs.push_back(make_run(scene, "restir-gather", 1, false, 0.05 * k, 1.0, options));
    report.runs.push_back(make_run(scene, "pt", 1, false, 0.8 * k, 0.5, options));
    report.runs.push_back(make_run(scene, "pt", 4, true, 0.3 * k, 2.0, options));
    EqualTime et;
    et.scene = scene;
    et.method = "restir-gather";
    et.method_median_ms = 4.0;
    et.pt_median_ms = 4.2;
    et.pt_spp = 4;
    et.method_mean = {0.02 * k, 0.01 * k, 0.05};
    et.pt_mean = {0.1 * k, 0.005 * k, 0.05};
    et.ratio = {0.2, 2.0, 1.0};
    report.equal_time.push_back(et);
    if (options.insets) {
      Insets insets{scene, options.frames - 1, {}};
      insets.images.emplace_back("reference", gradient_png(64, 48, 0.0f));
      insets.images.emplace_back("restir-gather", gradient_png(64, 48, 0.05f));
      insets.images.emplace_back("pt", gradient_png(64, 48, 0.4f));
      insets.images.emplace_back("error:restir-gather", error_png(64, 48, 0.2f));
      insets.images.emplace_back("error:pt", error_png(64, 48, 1.0f));
      report.insets.push_back(std::move(insets));
    }
  }
  return report;
}

}  // namespace strata::report::testing
