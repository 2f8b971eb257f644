#pragma once
// The stages a ReSTIR method composes (method_table.h, docs/ARCHITECTURE.md). Each one is
// declared in its own file with the passes it records and the state it reads and writes.
#include <memory>
#include <string>

#include "render/restir/restir_options.h"
#include "render/restir/stage.h"

namespace strata::render {

struct RestirState;
class SplatSortStage;

// primary: the visibility buffer (pixel-centre hits) -> visibility.current.
std::unique_ptr<Stage> make_primary_stage(const RestirState& state);
// domain_init (restir-multilayer): this frame's pixel-layer domains: propagation, representative
// hits, depth ranges, hole filling, the compacted list of active deep domains (ML 4.3, Sec. 5).
std::unique_ptr<Stage> make_domain_init_stage(const RestirState& state);
// initial: the canonical sample of every domain (restir_initial) -> work.
std::unique_ptr<Stage> make_initial_stage(const RestirState& state);
// temporal-gather: history.previous at the backprojected pixel, shifted and resampled with the
// canonical sample (restir_temporal); work, visibility -> work.
std::unique_ptr<Stage> make_temporal_gather_stage(const RestirState& state);
// temporal-splat (and with the method's `backup`, temporal-splat-backup): the splats that the splat
// sort (render/restir/splat_sort.h) landed in each pixel, resampled with its canonical sample
// (RS-main 4.1, 4.2); the sort's lists, work, visibility -> work.
std::unique_ptr<Stage> make_temporal_splat_stage(const RestirState& state, const SplatSortStage& sort);
// spatial: neighbours in a disk (restir_spatial); work -> history.current.
std::unique_ptr<Stage> make_spatial_stage(const RestirState& state);
// shade: the last resampling's estimate and the directly seen emission into the image (restir_shade); contribution -> accum.
std::unique_ptr<Stage> make_shade_stage(const RestirState& state);

// Why a history pass did not run this frame: no previous frame yet, or its pipelines still compile
// (MethodFrame::history_held).
std::string no_history_reason(bool held);

// What the temporal stage did with path suffixes this frame (option `suffix`; `changed_instances`:
// the swept boxes of GpuScene, which suffix auto tests a one-segment suffix against).
std::string suffix_decision(Suffix suffix_option, bool scene_moved, uint32_t changed_instances);

}  // namespace strata::render
