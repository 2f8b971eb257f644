#pragma once
// The calibration of `method auto` (service/method_auto.h; docs/ARCHITECTURE.md, "Method auto"): it
// renders the session's frames with two runs of each candidate, independent random streams each
// (pt only on the frames it is measured on), until the estimate decides (at most
// k_auto_calibration_frames frames), then hands over the chosen candidate's first run, whose
// GPU state (restir-gather's history) goes on as the session's renderer.
#include <array>
#include <cstdint>
#include <memory>
#include <optional>
#include <vector>

#include "gpu/context.h"
#include "render/renderer.h"
#include "scene/scene.h"
#include "service/method_auto.h"

namespace strata::service {

class AutoCalibration {
 public:
  // `reuse`: restir-gather's settings (the session's resolution and options); `requested_cap`: the
  // confidence cap the session asked for, if it did; `first_frame`: the session's frame index of the
  // calibration's first frame.
  AutoCalibration(const gpu::Context& ctx, const scene::Scene& scene, render::RenderSettings reuse,
                  std::optional<float> requested_cap, uint64_t first_frame);
  ~AutoCalibration();

  // Renders the calibration's next frame with its runs and returns the frame sent to the client:
  // the mean of restir-gather's two runs, with the first run's statistics. Its gpu_ms_total counts
  // every run (the others' time is the pass "auto_calibration"), its memory every run's.
  render::FrameResult render(const scene::FrameState& frame, uint32_t frame_index);
  bool done() const { return decided_; }
  uint64_t first_frame() const { return first_frame_; }
  // After done(): the choice, and the chosen candidate's first run (called once).
  const AutoChoice& choice() const { return choice_; }
  std::unique_ptr<render::Renderer> take_chosen();

 private:
  void estimate();  // the choice's figures over the frames measured so far

  const gpu::Context& ctx_;
  const scene::Scene& scene_;
  render::RenderSettings reuse_settings_;
  std::optional<float> requested_cap_;
  const uint64_t first_frame_;
  uint32_t frames_ = 0;
  bool decided_ = false;
  std::array<std::unique_ptr<render::Renderer>, 2> pt_, reuse_;
  std::vector<double> pt_relmse_, reuse_relmse_, pt_ms_, reuse_ms_;
  AutoChoice choice_;
};

}  // namespace strata::service
