#pragma once
// The temporal reuse of `restir-splat` (issue 5; RS-main 4.1, RS-supp 3.1): instead of gathering the
// backprojected previous pixel's reservoir, every previous reservoir is splatted forward into the
// pixel its primary hit lands in now, through a counting sort in four passes:
//   splat_project   per previous pixel: the forward shift and a count per current pixel
//   splat_scan      exclusive prefix sum of the counts
//   splat_insert    each landed splat into its pixel's range of the list
//   splat_resample  per current pixel: GRIS of the canonical sample with the splats that landed
#include <array>
#include <memory>

#include "gpu/buffer.h"
#include "gpu/pipeline.h"
#include "gpu/timer.h"
#include "render/method.h"

namespace strata::render {

class SplatTemporal {
 public:
  // Buffers of the owning method: its constants, the work reservoirs (canonical in, temporal out),
  // the two history buffers (the previous frame's final reservoirs in slot 1 - parity) and f(Y).
  SplatTemporal(const SharedResources& shared, uint32_t width, uint32_t height, const gpu::Buffer& restir_constants,
                const gpu::Buffer& work, const std::array<gpu::Buffer, 2>& history, const gpu::Buffer& contribution);
  ~SplatTemporal();
  void record(VkCommandBuffer cmd, gpu::PassTimer& timer, int parity);
  std::map<std::string, uint64_t> memory_bytes() const;

 private:
  struct Pass;
  uint32_t width_, height_;
  gpu::Buffer splats_, target_, count_, offsets_, list_;
  std::unique_ptr<Pass> project_, scan_, insert_, resample_;
};

}  // namespace strata::render
