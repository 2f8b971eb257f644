#include "eval_scoring.h"

#include <algorithm>
#include <cmath>
#include <limits>

namespace strata::client {
namespace {

// A ratio that stays finite when both errors are 0 (identical images).
double ratio(double a, double b) {
  constexpr double tiny = 1e-12;
  return (a + tiny) / (b + tiny);
}

report::Errors errors(const image::Image& test, const image::Image& ref, metrics::Mask mask, std::vector<float>* flip_map) {
  report::Errors e;
  e.relmse = metrics::relmse(test, ref, mask);
  e.relmse_luminance = metrics::relmse_luminance(test, ref, mask);
  e.mape = metrics::mape(test, ref, mask);
  metrics::HdrFlipResult flip = metrics::hdr_flip(test, ref, mask);
  e.flip = flip.mean;
  if (flip_map) *flip_map = std::move(flip.error_map);
  return e;
}

}  // namespace

report::FrameResult score_frame(const MethodImage& m, const ReferenceImage& ref, double cumulative_ms, std::vector<float>* flip_map) {
  report::FrameResult f;
  f.frame = m.frame;
  f.gpu_ms = m.gpu_ms;
  f.cumulative_ms = cumulative_ms + m.gpu_ms;
  f.pass_ms = m.pass_ms;
  f.whole = errors(m.image, ref.image, {}, flip_map);
  if (!ref.mask.empty()) {
    f.masked_pixels = uint64_t(std::count_if(ref.mask.begin(), ref.mask.end(), [](uint8_t v) { return v != 0; }));
    if (f.masked_pixels > 0) {
      f.has_masked = true;
      f.masked = errors(m.image, ref.image, ref.mask, nullptr);
    }
  }
  return f;
}

double median(std::vector<double> v) {
  if (v.empty()) return 0.0;
  std::sort(v.begin(), v.end());
  const size_t n = v.size();
  return n % 2 ? v[n / 2] : 0.5 * (v[n / 2 - 1] + v[n / 2]);
}

double median_gpu_ms(const report::Run& run) {
  if (!run.round_ms.empty()) return median(run.round_ms);  // --timing-rounds
  std::vector<double> ms;
  for (const auto& f : run.frames) ms.push_back(f.gpu_ms);
  return median(std::move(ms));
}

report::Errors mean_errors(const report::Run& run) {
  report::Errors e;
  if (run.frames.empty()) return e;
  for (const auto& f : run.frames) {
    e.relmse += f.whole.relmse;
    e.relmse_luminance += f.whole.relmse_luminance;
    e.mape += f.whole.mape;
    e.flip += f.whole.flip;
  }
  const double n = double(run.frames.size());
  e.relmse /= n;
  e.relmse_luminance /= n;
  e.mape /= n;
  e.flip /= n;
  return e;
}

uint32_t equal_time_spp(double method_median_ms, double pt_ms_per_spp, uint32_t max_spp) {
  if (!(pt_ms_per_spp > 0.0) || !std::isfinite(method_median_ms)) return 1;
  const double spp = std::floor(method_median_ms / pt_ms_per_spp);
  if (!(spp >= 1.0)) return 1;
  return uint32_t(std::min(spp, double(std::max(1u, max_spp))));
}

report::EqualTime equal_time_entry(const report::Run& method_run, const report::Run& pt_run) {
  report::EqualTime e;
  e.scene = method_run.scene;
  e.method = method_run.method;
  e.method_median_ms = median_gpu_ms(method_run);
  e.pt_median_ms = median_gpu_ms(pt_run);
  e.pt_spp = pt_run.spp;
  e.method_mean = mean_errors(method_run);
  e.pt_mean = mean_errors(pt_run);
  e.ratio.relmse = ratio(e.method_mean.relmse, e.pt_mean.relmse);
  e.ratio.mape = ratio(e.method_mean.mape, e.pt_mean.mape);
  e.ratio.flip = ratio(e.method_mean.flip, e.pt_mean.flip);
  const bool timed = e.method_median_ms > 0.0 && e.pt_median_ms > 0.0 && std::isfinite(e.method_median_ms / e.pt_median_ms);
  e.relmse_ratio_at_equal_ms = timed ? e.ratio.relmse * e.method_median_ms / e.pt_median_ms : e.ratio.relmse;
  return e;
}

}  // namespace strata::client
