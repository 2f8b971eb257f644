#pragma once
// Stage `splat sort` (the splat methods with temporal reuse; RS-supp 3.1): every previous reservoir
// (and, over an open shutter, each of its K time partitions, RS-main Eq. 19) is shifted forward to
// the pixel its primary hit lands in now, and the landed splats are sorted by pixel in three passes:
//   splat_project  per previous domain and time partition: the forward shift, a count per current domain
//   splat_scan     exclusive prefix sum of the counts -> RestirState::splat_offsets
//   splat_insert   each landed splat into its domain's range of the list
// It runs before the initial stage: the landing counts say which pixels no splat reached, and those
// take disocclusion_initial_candidates. The temporal-splat stage resamples what it hands on.
// restir-multilayer (ML 4.1, 4.2): the previous frame's active deep domains splat too (a second,
// indirect dispatch over their compacted list), into the front layer or the deeper domain whose
// depth range holds the splat.
#include <cstdint>
#include <memory>

#include "render/pass.h"
#include "render/restir/stage.h"

namespace strata::render {

struct RestirState;

// What the sort hands on to the temporal-splat stage: the splat records, the sorted list (with
// RestirState::splat_offsets) and whether and over how many time partitions it ran this frame.
struct SplatLists {
  gpu::Buffer splats;   // SplatRecord per previous domain and time partition
  gpu::Buffer target;   // the current domain each record landed in (SPLAT_NONE: none)
  gpu::Buffer count;    // per current domain: landed splats, then the insert cursor
  gpu::Buffer list;     // record indices sorted by current domain
  uint32_t allocated_partitions = 0;
  uint32_t generation = 0;  // bumped when the records were reallocated (passes that bind them rebind)
  bool ran = false;         // a previous frame existed: the sort ran and its lists are this frame's
  bool held = false;        // it did not run because the history passes are held (MethodFrame::history_held)
  uint32_t partitions = 1;  // K of this frame
};

class SplatSortStage : public Stage {
 public:
  explicit SplatSortStage(const RestirState& state);
  ~SplatSortStage() override;
  uint32_t timed_passes() const override { return 3; }
  // history.previous (and the previous frame's deep domain list) -> lists(), splat_offsets.
  void record(const StageFrame& f) override;
  PassDecision decision() const override;
  std::map<std::string, uint64_t> memory_bytes() const override;
  const SplatLists& lists() const { return lists_; }

 private:
  void allocate_records(uint32_t partitions);

  const RestirState& state_;
  SplatLists lists_;
  std::unique_ptr<Pass> project_, scan_, insert_;
  std::unique_ptr<Pass> project_deep_;  // restir-multilayer: the previous frame's active deep domains' list
};

}  // namespace strata::render
