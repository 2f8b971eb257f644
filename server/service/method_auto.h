#pragma once
// `method auto` (docs/ARCHITECTURE.md, "Method auto"): the session's default. It renders its first
// frames with both candidates, pt and restir-gather, twice each with independent random streams,
// estimates each one's RelMSE from the two runs' differences and its GPU time per frame, and keeps
// the one with the lower RelMSE x ms (the lower error at equal time). Here: the estimates, the choice
// and how the decisions say them; service/auto_calibration.h renders the runs.
#include <array>
#include <cstdint>
#include <optional>
#include <span>
#include <string>
#include <vector>

#include "image/image.h"
#include "render/method_table.h"
#include "strata/v1/render.pb.h"

namespace strata::service {

namespace v1 = ::strata::v1;

// The method a session takes when it names none, and the name that asks for the choice.
inline constexpr const char* k_auto_method = "auto";
// What a session may name: auto, then the method table's methods (ServerStatus.methods).
std::vector<std::string> session_methods();
// The candidates: the path tracer, and the ReSTIR method the service is built for.
inline constexpr const char* k_auto_pt = "pt";
inline constexpr const char* k_auto_reuse = "restir-gather";

// The calibration's frames, counted from where it starts. Every frame renders restir-gather twice
// (its history must build up in both runs); pt, which keeps no history, renders twice on frame 0 (its
// error per sample decides restir-gather's confidence cap) and on the measured frames,
// k_auto_first_measured.. (restir-gather's first frames have little history, and are not what the
// session would render from then on). The calibration ends on the first measured frame where the
// estimate is decisive (k_auto_decisive_ratio), at the latest after k_auto_calibration_frames.
inline constexpr uint32_t k_auto_calibration_frames = 5;
inline constexpr uint32_t k_auto_first_measured = 2;
// The estimate is decisive after n measured frames where restir-gather's RelMSE x ms over pt's lies
// outside [1 / k, k] with k = k_auto_decisive_ratio[n - 1]: one frame of 256x256 gives the ratio to
// well within 2x (restir-gather / pt at equal time: cornell 0.2-0.36, carousel-bounce 0.15-0.24,
// foliage 2.1-3.5; docs/BENCHMARKS.md), while near-ties (carousel 0.88-1.14, chess 1.2-1.4) take
// more frames. The last entry is 1: the calibration's last frame always decides.
inline constexpr std::array<double, 3> k_auto_decisive_ratio = {2.0, 1.5, 1.0};
static_assert(k_auto_first_measured + k_auto_decisive_ratio.size() == k_auto_calibration_frames);

// Each candidate's second run renders with the session's seed XOR this: another random stream.
inline constexpr uint32_t k_auto_second_run_seed = 0x9e3779b9u;

// Where pt's estimated RelMSE of one sample per pixel is at least this, the light is hard to find
// (most paths miss it, a few carry it: carousel-bounce 5.7, against 0.03-0.21 on carousel, chess,
// foliage and cornell; docs/BENCHMARKS.md), and restir-gather's confidence cap where something
// moved is k_auto_hard_light_cap instead of the method's 2: there a resampled path is worth more
// than the fit it loses under motion (carousel-bounce: cap 4 -17% RelMSE, where carousel pays
// 5-23% for it).
inline constexpr double k_auto_hard_light_relmse = 1.0;
inline constexpr float k_auto_hard_light_cap = 4.0f;

// A reference estimate from independent runs of one frame: per pixel and channel the median over
// the 3x3 neighbourhood (clamped at the border) of the runs' mean, so that one run's firefly does
// not move it. Every run has the size of the first.
image::Image robust_reference(std::span<const image::Image* const> runs);

// The RelMSE (docs/BENCHMARKS.md: the mean over pixels and RGB of (x - r)^2 / (r^2 + 0.01)) of one
// of two independent runs `a` and `b` of an unbiased estimator against the reference estimate
// `ref`: E[(a - b)^2] = 2 Var, so (a - b)^2 / 2 stands for (x - r)^2. Non-finite terms count 0.
double paired_relmse(const image::Image& a, const image::Image& b, const image::Image& ref);

// One candidate's figures over the measured frames.
struct CandidateEstimate {
  double relmse = 0.0;  // mean over the measured frames of paired_relmse
  double ms = 0.0;      // least GPU ms of one frame over the measured frames and both runs
  double product() const { return relmse * ms; }
};

// What auto chose at one resolution, and the figures it chose by.
struct AutoChoice {
  const render::MethodSpec* method = nullptr;  // pt or restir-gather
  CandidateEstimate pt, reuse;
  double pt_first_relmse = 0.0;  // pt's estimate on the calibration's first frame (the cap's figure)
  float confidence_cap = 0.0f;   // restir-gather's cap where something moved, as the calibration ran it
  bool cap_chosen = false;       // chosen by auto (false: the session asked for one)
  uint64_t first_frame = 0;      // the session's frame the calibration started at
  uint32_t measured_frames = 0;  // frames measured (from first_frame + k_auto_first_measured)
  uint32_t width = 0, height = 0;
  // restir-gather's RelMSE x ms over pt's: below 1 restir-gather wins at equal time.
  double ratio() const { return pt.product() > 0.0 ? reuse.product() / pt.product() : 0.0; }
};

// restir-gather's cap where something moved: the requested one, else k_auto_hard_light_cap where
// pt's RelMSE per sample reaches k_auto_hard_light_relmse, else the method's.
float auto_confidence_cap(double pt_first_relmse, std::optional<float> requested);

// Whether the estimate after `measured_frames` measured frames decides (k_auto_decisive_ratio).
bool auto_decisive(const CandidateEstimate& pt, const CandidateEstimate& reuse, uint32_t measured_frames);

// The candidate with the lower RelMSE x ms; pt on a tie and when restir-gather's figures are not
// finite.
const render::MethodSpec& auto_method(const CandidateEstimate& pt, const CandidateEstimate& reuse);

// The `method` decision's reason: "auto: restir-gather (est. RelMSE x ms 0.31 of pt's over frames 2..4 ...)".
std::string auto_method_reason(const AutoChoice& c);
// The `confidence_cap` decision's reason where auto chose it.
std::string auto_cap_reason(const AutoChoice& c);

// Rewrites the `method` decision (and `confidence_cap`'s where auto chose it) of a session whose
// method is auto: `choice` when it has chosen (its method set), else it is calibrating since
// `calibrating_from` (and `choice`, when present, holds the cap chosen on its first frame).
void describe_auto(std::vector<v1::Decision>& decisions, const std::string& requested_method,
                   const std::optional<AutoChoice>& choice, uint64_t calibrating_from, const std::string& why_calibrating);

}  // namespace strata::service
