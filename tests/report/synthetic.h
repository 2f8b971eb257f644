#pragma once
// A synthetic evaluation report for the report tests: no renderer involved.
#include <cstdint>

#include "report/report.h"

namespace strata::report::testing {

struct SyntheticOptions {
  uint32_t scenes = 2;
  uint32_t frames = 8;
  bool masked = true;   // disoccluded-pixel errors on every frame but the first
  bool insets = true;   // reference, two methods and their error maps (64x48 PNGs)
};

// Per scene three runs, "restir-gather" (1 spp), "pt" (1 spp) and the equal-time pt (4 spp),
// with decreasing, distinct errors; per-pass timings; one equal-time entry per scene. Scene names
// are "cornell" and "chess" (then "scene-N"); meta carries a "</script>" to exercise escaping.
Report synthetic_report(const SyntheticOptions& options = {});

}  // namespace strata::report::testing
