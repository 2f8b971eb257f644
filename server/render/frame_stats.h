#pragma once
// What every frame reports (docs/ARCHITECTURE.md, Statistics): GPU time per pass, counters, memory, and which
// passes ran or were left out and why.
#include <cstdint>
#include <map>
#include <string>
#include <vector>

#include <nlohmann/json_fwd.hpp>

#include "gpu/timer.h"

namespace strata::render {

struct PassDecision {
  std::string pass;
  bool ran = false;
  std::string reason;  // why it was left out (or which variant ran)
};

struct FrameStats {
  uint32_t frame = 0;
  uint64_t pixels = 0;                            // width * height of the frame
  std::vector<gpu::PassTime> pass_ms;
  double gpu_ms_total = 0.0;
  std::map<std::string, uint64_t> rays_traced;   // by kind (pt: primary, bounce, shadow) or by pass (ReSTIR)
  std::map<std::string, uint64_t> reuse;          // ReSTIR: shifts attempted, samples taken from history/neighbours
  std::map<std::string, uint64_t> shift_failures; // ReSTIR: by pass and reason (restir_data.h SHIFT_FAIL_*)
  uint64_t paths = 0;
  uint64_t nonfinite_rejected = 0;                // non-finite samples and weights zeroed (and counted)
  std::map<std::string, uint64_t> memory_bytes;   // by buffer group
  std::vector<PassDecision> passes;
  uint32_t tlas_builds = 0;
  uint32_t tlas_refits = 0;
  uint64_t rays_total() const;
};

nlohmann::json to_json(const FrameStats& s);

}  // namespace strata::render
