#pragma once
// The temporal reuse of `restir-splat` (issue 5; RS-main 4.1, RS-supp 3.1): instead of gathering the
// backprojected previous pixel's reservoir, every previous reservoir is splatted forward into the
// pixel its primary hit lands in now, through a counting sort in four passes:
//   splat_project   per previous pixel (and time partition): the forward shift and a count per current pixel
//   splat_scan      exclusive prefix sum of the counts
//   splat_insert    each landed splat into its pixel's range of the list
// Over an open shutter every previous reservoir splats into K time partitions (RS-main Eq. 19).
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
  // `partitions`: K of this frame (1 unless the shutter is open and the camera moves over it).
  void record(VkCommandBuffer cmd, gpu::PassTimer& timer, int parity, uint32_t partitions);
  std::map<std::string, uint64_t> memory_bytes() const;

 private:
  struct Pass;
  void ensure_partitions(uint32_t partitions);
  const SharedResources shared_;  // references to the renderer's resources
  uint32_t width_, height_;
  uint32_t partitions_ = 0;  // K the splat records are allocated for
  gpu::Buffer splats_, target_, count_, offsets_, list_;
  std::unique_ptr<Pass> project_, scan_, insert_, resample_;
};

}  // namespace strata::render
