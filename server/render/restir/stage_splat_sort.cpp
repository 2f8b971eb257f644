#include "render/restir/splat_sort.h"

#include "include/bindings.h"
#include "include/frame_data.h"
#include "render/frame_constants.h"
#include "render/restir/restir_state.h"
#include "render/restir/stages.h"
#include "restir/splat_data.h"

namespace strata::render {

SplatSortStage::SplatSortStage(const RestirState& state) : state_(state) {
  const auto& ctx = state.shared.ctx;
  lists_.count = device_storage(ctx, sizeof(uint32_t) * state.domains, "splat counts");
  allocate_records(1);
  const GpuScene* scene = &state.shared.scene;
  const SceneUse with_history{.lights = true, .history = true};  // lights: the suffix replay's NEE end
  const uint32_t stepping = state.layer_stepping() ? VK_TRUE : VK_FALSE;  // layers by rank (restir/layers.glsl)
  auto project = [&](bool deep) {
    return std::make_unique<Pass>(
        ctx, scene, with_history, "restir_splat_project",
        restir_resources(state, storage(BINDING_RESERVOIRS_OUT, Access::read_write, state.work),
                         {history_previous(BINDING_RESERVOIRS_IN, state.history),
                          storage(BINDING_SPLATS, Access::write, lists_.splats),
                          storage(BINDING_SPLAT_TARGET, Access::write, lists_.target),
                          storage(BINDING_SPLAT_COUNT, Access::read_write, lists_.count),
                          // The domains' depth ranges of both frames: a splat's layer (restir/layers.glsl).
                          history_current(BINDING_DOMAINS, Access::read, state.domain_ranges),
                          history_previous(BINDING_DOMAINS_PREV, state.domain_ranges),
                          history_previous(BINDING_DOMAIN_LIST_PREV, state.domain_list),
                          history_previous(BINDING_DOMAIN_ARGS_PREV, state.domain_args)}),
        std::vector<gpu::SpecConstant>{{SPEC_DOMAIN_LIST, deep ? VK_TRUE : VK_FALSE}, {SPEC_LAYER_STEPPING, stepping}});
  };
  project_ = project(false);
  if (state.multilayer()) project_deep_ = project(true);
  scan_ = std::make_unique<Pass>(ctx, nullptr, SceneUse{}, "restir_splat_scan",
                                 std::vector<PassResource>{uniform(BINDING_FRAME, state.shared.constants),
                                                           uniform(BINDING_RESTIR, state.constants),
                                                           storage(BINDING_SPLAT_COUNT, Access::read, lists_.count),
                                                           storage(BINDING_SPLAT_OFFSETS, Access::write, state.splat_offsets)});
  insert_ = std::make_unique<Pass>(ctx, nullptr, SceneUse{}, "restir_splat_insert",
                                   std::vector<PassResource>{uniform(BINDING_FRAME, state.shared.constants),
                                                             uniform(BINDING_RESTIR, state.constants),
                                                             storage(BINDING_SPLAT_TARGET, Access::read, lists_.target),
                                                             storage(BINDING_SPLAT_COUNT, Access::read_write, lists_.count),
                                                             storage(BINDING_SPLAT_OFFSETS, Access::read, state.splat_offsets),
                                                             storage(BINDING_SPLAT_LIST, Access::write, lists_.list)});
}

SplatSortStage::~SplatSortStage() = default;

// Records, targets and the list grow with K (multi-splatting, RS-main Eq. 19) the first time a
// frame's shutter needs it: a session that never opens the shutter keeps one partition.
void SplatSortStage::allocate_records(uint32_t partitions) {
  const auto& ctx = state_.shared.ctx;
  const size_t records = state_.domains * partitions;
  lists_.splats = device_storage(ctx, sizeof(gpu::SplatRecord) * records, "splats");
  lists_.target = device_storage(ctx, sizeof(uint32_t) * records, "splat targets");
  lists_.list = device_storage(ctx, sizeof(uint32_t) * records, "splat list");
  lists_.allocated_partitions = partitions;
  ++lists_.generation;
}

void SplatSortStage::record(const StageFrame& f) {
  lists_.ran = f.frame.history_valid;
  lists_.held = f.frame.history_held;
  if (!lists_.ran) return;
  // K of this frame (RS-main Eq. 19), as the passes read it from the frame constants.
  lists_.partitions = time_partitions(f.frame.frame, state_.settings.restir.splats_per_frame);
  if (lists_.partitions > lists_.allocated_partitions) {
    allocate_records(lists_.partitions);
    for (Pass* p : {project_.get(), project_deep_.get(), insert_.get()})
      if (p) p->rebind();
  }
  const uint32_t w = state_.width, h = state_.height;
  timed(f, "splat_project", [&] {
    vkCmdFillBuffer(f.cmd, lists_.count.handle(), 0, VK_WHOLE_SIZE, 0);
    // Every record lands nowhere until its splat lands (domains the list dispatch leaves out included).
    vkCmdFillBuffer(f.cmd, lists_.target.handle(), 0, VK_WHOLE_SIZE, gpu::SPLAT_NONE);
    gpu::compute_barrier(f.cmd);
    project_->dispatch_layers(f.cmd, f.parity, w, h, lists_.partitions);  // the front layer; z: the time partition
    if (project_deep_) project_deep_->dispatch_indirect(f.cmd, f.parity, state_.domain_args.previous(f.parity));
  });
  timed(f, "splat_scan", [&] { scan_->dispatch_1d(f.cmd, f.parity, 1); });
  timed(f, "splat_insert", [&] { insert_->dispatch_layers(f.cmd, f.parity, w, h, state_.layers * lists_.partitions); });
}

PassDecision SplatSortStage::decision() const {
  if (!lists_.ran) return {"splat_sort", false, no_history_reason(lists_.held)};
  return {"splat_sort", true,
          "counting sort of the previous reservoirs' forward splats" +
              (lists_.partitions > 1 ? " over " + std::to_string(lists_.partitions) + " time partitions" : std::string()) +
              (project_deep_ ? ", the active deep domains' included" : "")};
}

std::map<std::string, uint64_t> SplatSortStage::memory_bytes() const {
  return {{"splats", lists_.splats.size() + lists_.target.size() + lists_.count.size() + state_.splat_offsets.size() +
                         lists_.list.size()}};
}

}  // namespace strata::render
