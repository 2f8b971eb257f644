#include "service/method_auto.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <stdexcept>


namespace strata::service {
namespace {

std::string fixed(double v, int digits) {
  char buf[64];
  std::snprintf(buf, sizeof buf, "%.*f", digits, v);
  return buf;
}

// Three significant digits: RelMSE spans 0.001 to 10.
std::string sig3(double v) {
  char buf[64];
  std::snprintf(buf, sizeof buf, "%.3g", v);
  return buf;
}

std::string frames_text(const AutoChoice& c) {
  const uint64_t first = c.first_frame + k_auto_first_measured;
  return c.measured_frames <= 1 ? "frame " + std::to_string(first)
                                : "frames " + std::to_string(first) + ".." + std::to_string(first + c.measured_frames - 1);
}

}  // namespace

std::vector<std::string> session_methods() {
  std::vector<std::string> names{k_auto_method};
  for (const auto& m : render::available_methods()) names.push_back(m);
  return names;
}

image::Image robust_reference(std::span<const image::Image* const> runs) {
  if (runs.empty()) throw std::invalid_argument("robust_reference: no runs");
  const uint32_t w = runs[0]->width, h = runs[0]->height;
  for (const auto* r : runs)
    if (r->width != w || r->height != h) throw std::invalid_argument("robust_reference: the runs differ in size");
  image::Image mean{w, h, std::vector<float>(size_t(4) * w * h, 0.0f)};
  for (const auto* r : runs)
    for (size_t i = 0; i < mean.rgba.size(); ++i) {
      const float v = r->rgba[i];
      mean.rgba[i] += std::isfinite(v) ? v / float(runs.size()) : 0.0f;
    }
  image::Image ref = mean;
  std::array<float, 9> window{};
  for (uint32_t y = 0; y < h; ++y)
    for (uint32_t x = 0; x < w; ++x)
      for (int ch = 0; ch < 3; ++ch) {
        size_t n = 0;
        for (int dy = -1; dy <= 1; ++dy)
          for (int dx = -1; dx <= 1; ++dx) {
            const uint32_t sx = uint32_t(std::clamp<int>(int(x) + dx, 0, int(w) - 1));
            const uint32_t sy = uint32_t(std::clamp<int>(int(y) + dy, 0, int(h) - 1));
            window[n++] = mean.pixel(sx, sy)[ch];
          }
        std::nth_element(window.begin(), window.begin() + 4, window.end());
        ref.pixel(x, y)[ch] = window[4];
      }
  return ref;
}

double paired_relmse(const image::Image& a, const image::Image& b, const image::Image& ref) {
  if (a.width != b.width || a.height != b.height || a.width != ref.width || a.height != ref.height)
    throw std::invalid_argument("paired_relmse: the images differ in size");
  const size_t pixels = size_t(a.width) * a.height;
  if (pixels == 0) return 0.0;
  double sum = 0.0;
  for (size_t p = 0; p < pixels; ++p)
    for (size_t ch = 0; ch < 3; ++ch) {
      const double d = double(a.rgba[4 * p + ch]) - double(b.rgba[4 * p + ch]);
      const double r = ref.rgba[4 * p + ch];
      const double term = 0.5 * d * d / (r * r + 0.01);
      if (std::isfinite(term)) sum += term;
    }
  return sum / double(3 * pixels);
}

float auto_confidence_cap(double pt_first_relmse, std::optional<float> requested) {
  if (requested) return *requested;
  if (pt_first_relmse >= k_auto_hard_light_relmse) return k_auto_hard_light_cap;
  return render::method_spec(k_auto_reuse).confidence_cap;
}

bool auto_decisive(const CandidateEstimate& pt, const CandidateEstimate& reuse, uint32_t measured_frames) {
  if (measured_frames == 0) return false;
  if (measured_frames >= k_auto_decisive_ratio.size()) return true;
  const double k = k_auto_decisive_ratio[measured_frames - 1];
  if (!(pt.product() > 0.0) || !std::isfinite(reuse.product())) return false;  // decided by more frames
  const double ratio = reuse.product() / pt.product();
  return ratio < 1.0 / k || ratio > k;
}

const render::MethodSpec& auto_method(const CandidateEstimate& pt, const CandidateEstimate& reuse) {
  // pt's RelMSE x spp is constant (docs/BENCHMARKS.md, "How methods are compared"), so at the
  // other's frame time a candidate's error is its RelMSE x ms over that time: the lower product wins.
  const bool reuse_wins = std::isfinite(reuse.product()) && reuse.product() < pt.product();
  return render::method_spec(reuse_wins ? k_auto_reuse : k_auto_pt);
}

std::string auto_method_reason(const AutoChoice& c) {
  if (!c.method) return "auto: calibrating";
  const std::string other = c.method->name == std::string(k_auto_pt) ? k_auto_reuse : k_auto_pt;
  const double ratio = c.ratio();
  return std::string("auto: ") + c.method->name + " (est. RelMSE x ms of restir-gather " + fixed(ratio, 2) +
         " of pt's over " + frames_text(c) + " at " + std::to_string(c.width) + "x" + std::to_string(c.height) +
         ": pt " + sig3(c.pt.relmse) + " x " + fixed(c.pt.ms, 1) + " ms, restir-gather " + sig3(c.reuse.relmse) + " x " +
         fixed(c.reuse.ms, 1) + " ms; " + (ratio < 1.0 ? "below 1" : "not below 1") + ": " + c.method->name +
         " has the lower error at equal GPU time, " + other +
         " was left). Each candidate rendered each frame twice with independent random streams; its RelMSE is "
         "estimated from the two runs' differences against their 3x3-median mean. Calibrated again when the "
         "resolution changes, an instance that emits light moves or a punctual light moves";
}

std::string auto_cap_reason(const AutoChoice& c) {
  const bool hard = c.pt_first_relmse >= k_auto_hard_light_relmse;
  return "auto: temporal confidence is clamped to this where something moved; pt's est. RelMSE per sample on frame " +
         std::to_string(c.first_frame) + " is " + sig3(c.pt_first_relmse) + (hard ? " >= " : " < ") +
         sig3(k_auto_hard_light_relmse) +
         (hard ? ": the light is hard to find, and the history's paths are worth more than the fit they lose "
                 "under motion (docs/BENCHMARKS.md, carousel-bounce: cap 4 -17%)"
               : ": restir-gather's own cap (docs/ARCHITECTURE.md, \"Confidence cap\")");
}

void describe_auto(std::vector<v1::Decision>& decisions, const std::string& requested_method,
                   const std::optional<AutoChoice>& choice, uint64_t calibrating_from, const std::string& why_calibrating) {
  for (auto& d : decisions) {
    if (d.name() == "method") {
      d.set_requested(requested_method);
      if (choice && choice->method) {
        d.set_value(choice->method->name);
        d.set_reason(auto_method_reason(*choice) + "; " + choice->method->summary);
      } else {
        d.set_value(k_auto_reuse);
        d.set_reason("auto: calibrating from frame " + std::to_string(calibrating_from) + " for " +
                     std::to_string(k_auto_first_measured + 1) + " to " + std::to_string(k_auto_calibration_frames) +
                     " frames (" + why_calibrating +
                     "): restir-gather renders every frame twice and pt frame " + std::to_string(calibrating_from) +
                     " and frames " + std::to_string(calibrating_from + k_auto_first_measured) +
                     ".. twice, and the one with the lower estimated RelMSE x GPU ms is kept; the frames sent meanwhile "
                     "are the mean of restir-gather's two runs");
      }
    } else if (d.name() == "confidence_cap" && choice && choice->cap_chosen && d.applies()) {
      d.set_reason(auto_cap_reason(*choice));
    }
  }
}

}  // namespace strata::service
