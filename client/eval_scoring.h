#pragma once
// The numbers of `strata eval`: a method's frame scored against its reference (RelMSE, MAPE,
// HDR-FLIP; the same over the disoccluded pixels when the reference has a mask), medians and
// means over a run, and the equal-time comparison of a method with pt.
#include <cstdint>
#include <vector>

#include "eval_runner.h"
#include "metrics/metrics.h"
#include "report/report.h"

namespace strata::client {

// Scores `m` against `ref`. `cumulative_ms` is the run's GPU time before this frame. The frame's
// HDR-FLIP map (whole image) goes to `flip_map` when given.
report::FrameResult score_frame(const MethodImage& m, const ReferenceImage& ref, double cumulative_ms,
                                std::vector<float>* flip_map = nullptr);

double median(std::vector<double> values);
// A run's time: the median of its frames' GPU ms, or with --timing-rounds the median of its rounds' (Run::round_ms).
double median_gpu_ms(const report::Run& run);
report::Errors mean_errors(const report::Run& run);  // over frames, whole image

// pt's samples per frame at a method's median frame time: max(1, floor(method_ms / pt_ms_per_spp)),
// at most `max_spp`.
uint32_t equal_time_spp(double method_median_ms, double pt_ms_per_spp, uint32_t max_spp);

// The equal-time entry of `method_run` against `pt_run` (pt at pt_run.spp samples per frame).
report::EqualTime equal_time_entry(const report::Run& method_run, const report::Run& pt_run);

}  // namespace strata::client
