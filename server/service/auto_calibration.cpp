#include "service/auto_calibration.h"

#include <algorithm>
#include <cmath>
#include <numeric>

namespace strata::service {
namespace {

// The least of a candidate's frame times: lavapipe's GPU time is CPU time that other processes on
// the machine only add to (pt at 64x64 read 8 to 16 ms a frame within one minute on a loaded
// 2-core VM), so the least time is its own cost.
double least(const std::vector<double>& v) { return v.empty() ? 0.0 : *std::min_element(v.begin(), v.end()); }

double mean(const std::vector<double>& v) {
  return v.empty() ? 0.0 : std::accumulate(v.begin(), v.end(), 0.0) / double(v.size());
}

std::array<std::unique_ptr<render::Renderer>, 2> two_runs(const gpu::Context& ctx, const scene::Scene& scene,
                                                          const render::RenderSettings& s) {
  render::RenderSettings second = s;
  second.seed = s.seed ^ k_auto_second_run_seed;
  return {std::make_unique<render::Renderer>(ctx, scene, s), std::make_unique<render::Renderer>(ctx, scene, second)};
}

// Adds the runs not sent to the client to the one sent: their GPU time as the pass
// "auto_calibration", their memory as the group of that name.
void add_other_runs(render::FrameResult& shown, std::span<const render::FrameResult> others) {
  double ms = 0.0;
  uint64_t bytes = 0;
  for (const auto& o : others) {
    ms += o.stats.gpu_ms_total;
    for (const auto& [group, b] : o.stats.memory_bytes) bytes += b;
  }
  shown.stats.pass_ms.push_back({"auto_calibration", ms});
  shown.stats.gpu_ms_total += ms;
  shown.stats.memory_bytes["auto_calibration"] += bytes;
}

}  // namespace

AutoCalibration::AutoCalibration(const gpu::Context& ctx, const scene::Scene& scene, render::RenderSettings reuse,
                                 std::optional<float> requested_cap, uint64_t first_frame)
    : ctx_(ctx), scene_(scene), reuse_settings_(std::move(reuse)), requested_cap_(requested_cap), first_frame_(first_frame) {
  reuse_settings_.method = k_auto_reuse;
  render::RenderSettings pt = reuse_settings_;
  pt.method = k_auto_pt;
  pt_ = two_runs(ctx_, scene_, pt);
  choice_.width = reuse_settings_.width;
  choice_.height = reuse_settings_.height;
  choice_.first_frame = first_frame;
}

AutoCalibration::~AutoCalibration() = default;

render::FrameResult AutoCalibration::render(const scene::FrameState& frame, uint32_t frame_index) {
  const uint32_t k = frames_++;
  const bool measured = k >= k_auto_first_measured;
  std::vector<render::FrameResult> pt;  // pt's two runs, where it renders
  if (k == 0 || measured)
    for (const auto& run : pt_) pt.push_back(run->render(frame, frame_index));
  if (k == 0) {
    // pt's error per sample: how hard the light is to find, which sets restir-gather's cap before
    // restir-gather's runs start (on this same frame, so that its first run is what a restir-gather
    // session with that cap renders).
    const std::array<const image::Image*, 2> runs = {&pt[0].image, &pt[1].image};
    choice_.pt_first_relmse = paired_relmse(pt[0].image, pt[1].image, robust_reference(runs));
    choice_.cap_chosen = !requested_cap_;
    choice_.confidence_cap = auto_confidence_cap(choice_.pt_first_relmse, requested_cap_);
    reuse_settings_.restir.confidence_cap = choice_.confidence_cap;
    reuse_ = two_runs(ctx_, scene_, reuse_settings_);
  }
  std::array<render::FrameResult, 2> reuse = {reuse_[0]->render(frame, frame_index), reuse_[1]->render(frame, frame_index)};
  if (measured) {
    const std::array<const image::Image*, 4> runs = {&pt[0].image, &pt[1].image, &reuse[0].image, &reuse[1].image};
    const image::Image ref = robust_reference(runs);
    pt_relmse_.push_back(paired_relmse(pt[0].image, pt[1].image, ref));
    reuse_relmse_.push_back(paired_relmse(reuse[0].image, reuse[1].image, ref));
    for (const auto& r : pt) pt_ms_.push_back(r.stats.gpu_ms_total);
    for (const auto& r : reuse) reuse_ms_.push_back(r.stats.gpu_ms_total);
    estimate();
    decided_ = auto_decisive(choice_.pt, choice_.reuse, choice_.measured_frames);
  }
  // The frame sent: the mean of restir-gather's two runs, independent unbiased estimates of the same
  // frame, so half the variance of either at no further cost; its statistics are the first run's.
  render::FrameResult shown = std::move(reuse[0]);
  const std::vector<float>& second = reuse[1].image.rgba;
  for (size_t i = 0; i < shown.image.rgba.size(); ++i) shown.image.rgba[i] = 0.5f * (shown.image.rgba[i] + second[i]);
  std::vector<render::FrameResult> others;
  others.push_back(std::move(reuse[1]));
  for (auto& r : pt) others.push_back(std::move(r));
  add_other_runs(shown, others);
  if (done()) choice_.method = &auto_method(choice_.pt, choice_.reuse);
  return shown;
}

void AutoCalibration::estimate() {
  choice_.pt = {mean(pt_relmse_), least(pt_ms_)};
  choice_.reuse = {mean(reuse_relmse_), least(reuse_ms_)};
  choice_.measured_frames = uint32_t(pt_relmse_.size());
}

std::unique_ptr<render::Renderer> AutoCalibration::take_chosen() {
  return std::move(choice_.method->reuse ? reuse_[0] : pt_[0]);
}

}  // namespace strata::service
