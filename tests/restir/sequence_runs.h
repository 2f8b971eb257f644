#pragma once
// Runs of a method over a short frame sequence for the unbiasedness harness (unbiasedness.h): the
// mean image of frames 1 .. F-1 (those that reuse history) of one run, and a converged path-traced
// reference of the same frames from fresh renderers.
#include <cstdint>
#include <functional>
#include <string>

#include "image/image.h"
#include "render/renderer.h"
#include "scene/scene.h"
#include "support/unbiasedness.h"

namespace strata::test {

struct SequenceRun {
  std::string method = "pt";
  uint32_t size = 16;    // width = height
  uint32_t frames = 4;   // the first one has no history and is left out of the mean
  uint32_t max_depth = 4;
  std::function<scene::FrameState(const scene::Scene&, uint32_t)> state = [](const scene::Scene& s, uint32_t) {
    return s.frame_state(0);
  };
  std::function<void(render::RestirOptions&)> options = [](render::RestirOptions&) {};
};

// One run (seed `seed`, `spp` samples a frame) of the method over the sequence: its frames 1 .. F-1's mean.
image::Image sequence_mean(const scene::Scene& s, const SequenceRun& run, uint32_t seed, uint32_t spp = 1);

// `runs` independent pt renders (spp each) of frames 1 .. F-1, each frame from a fresh renderer.
RunningImage pt_reference(const scene::Scene& s, const SequenceRun& run, uint32_t runs, uint32_t spp);

// One unbiasedness case: `runs` runs of the method (seeds 1000 + r) against a pt reference of
// `reference_runs` renders x `reference_spp` (seeds as pt_reference draws them), compared in 4 x 4
// pixel blocks (support/unbiasedness.h); prints the report under `name` and fails the test when
// the method's mean differs.
void expect_matches_pt(const scene::Scene& s, const std::string& name, const SequenceRun& run, uint32_t runs,
                       uint32_t reference_runs, uint32_t reference_spp);

}  // namespace strata::test
