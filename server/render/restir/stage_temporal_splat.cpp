// Stage `temporal-splat` (restir-splat; RS-main 4.1, RS-supp 3.1) and, with the method's `backup`,
// `temporal-splat-backup` (restir-splat-backup; RS-main 4.2): instead of gathering the backprojected
// previous pixel's reservoir, every previous reservoir is splatted forward into the pixel its
// primary hit lands in now, through a counting sort in four passes:
//   splat_project   per previous pixel (and time partition): the forward shift and a count per current pixel
//   splat_scan      exclusive prefix sum of the counts
//   splat_insert    each landed splat into its pixel's range of the list
//   splat_resample  per current pixel: GRIS of the canonical sample with the splats that landed
//                   (and the backup sample, shifted from the backprojected previous pixel)
// Over an open shutter every previous reservoir splats into K time partitions (RS-main Eq. 19).
// restir-multilayer (ML 4.1, 4.2): every active previous domain (pixel, layer) splats, into the front
// layer or the deeper domain whose depth range holds it: the front layer's in the image dispatch,
// the deep ones in a second dispatch over the previous frame's compacted list; the counting sort
// runs over all domains, and a second resampling dispatch runs this frame's list.
#include "include/bindings.h"
#include "include/frame_data.h"
#include "options/option_table.h"
#include "render/frame_constants.h"
#include "render/restir/restir_state.h"
#include "render/restir/stages.h"
#include "restir/splat_data.h"

namespace strata::render {
namespace {

class TemporalSplatStage : public Stage {
 public:
  explicit TemporalSplatStage(const RestirState& state)
      : state_(state),
        count_(device_storage(state.shared.ctx, sizeof(uint32_t) * state.domains, "splat counts")),
        offsets_(state.splat_offsets) {
    allocate_records(1);
    const auto& ctx = state.shared.ctx;
    const GpuScene* scene = &state.shared.scene;
    const SceneUse with_history{.lights = true, .history = true};  // lights: the suffix replay's NEE end
    auto out = [&] { return storage(BINDING_RESERVOIRS_OUT, Access::read_write, state.work); };
    auto in = [&] { return history_previous(BINDING_RESERVOIRS_IN, state.history); };
    // The domains' depth ranges of both frames: a splat's layer (restir/layers.glsl).
    auto ranges = [&] { return history_current(BINDING_DOMAINS, Access::read, state.domain_ranges); };
    auto ranges_prev = [&] { return history_previous(BINDING_DOMAINS_PREV, state.domain_ranges); };
    const uint32_t stepping = state.layer_stepping() ? VK_TRUE : VK_FALSE;  // layers by rank (restir/layers.glsl)
    auto project = [&](bool deep) {
      return std::make_unique<Pass>(ctx, scene, with_history, "restir_splat_project",
                                    restir_resources(state, out(),
                                                     {in(), storage(BINDING_SPLATS, Access::write, splats_),
                                                      storage(BINDING_SPLAT_TARGET, Access::write, target_),
                                                      storage(BINDING_SPLAT_COUNT, Access::read_write, count_), ranges(), ranges_prev(),
                                                      history_previous(BINDING_DOMAIN_LIST_PREV, state.domain_list),
                                                      history_previous(BINDING_DOMAIN_ARGS_PREV, state.domain_args)}),
                                    std::vector<gpu::SpecConstant>{{SPEC_DOMAIN_LIST, deep ? VK_TRUE : VK_FALSE}, {SPEC_LAYER_STEPPING, stepping}});
    };
    project_ = project(false);
    if (state.multilayer()) project_deep_ = project(true);
    scan_ = std::make_unique<Pass>(ctx, nullptr, SceneUse{}, "restir_splat_scan",
                                   std::vector<PassResource>{uniform(BINDING_FRAME, state.shared.constants),
                                                             uniform(BINDING_RESTIR, state.constants),
                                                             storage(BINDING_SPLAT_COUNT, Access::read, count_),
                                                             storage(BINDING_SPLAT_OFFSETS, Access::write, offsets_)});
    insert_ = std::make_unique<Pass>(ctx, nullptr, SceneUse{}, "restir_splat_insert",
                                     std::vector<PassResource>{uniform(BINDING_FRAME, state.shared.constants),
                                                               uniform(BINDING_RESTIR, state.constants),
                                                               storage(BINDING_SPLAT_TARGET, Access::read, target_),
                                                               storage(BINDING_SPLAT_COUNT, Access::read_write, count_),
                                                               storage(BINDING_SPLAT_OFFSETS, Access::read, offsets_),
                                                               storage(BINDING_SPLAT_LIST, Access::write, list_)});
    auto resample = [&](bool deep) {
      return std::make_unique<Pass>(ctx, scene, with_history, "restir_splat_resample",
                                    restir_resources(state, out(),
                                                     {in(), storage(BINDING_SPLATS, Access::read, splats_),
                                                      storage(BINDING_SPLAT_OFFSETS, Access::read, offsets_),
                                                      storage(BINDING_SPLAT_LIST, Access::read, list_),
                                                      history_current(BINDING_PRIMARY, Access::read, state.visibility),
                                                      // read_write: the front layer's DOMAIN_COVERED flag
                                                      history_current(BINDING_DOMAINS, Access::read_write, state.domain_ranges),
                                                      ranges_prev(), history_current(BINDING_DOMAIN_LIST, Access::read, state.domain_list),
                                                      history_current(BINDING_DOMAIN_ARGS, Access::read, state.domain_args)}),
                                    std::vector<gpu::SpecConstant>{{SPEC_DOMAIN_LIST, deep ? VK_TRUE : VK_FALSE}, {SPEC_LAYER_STEPPING, stepping}});
    };
    resample_ = resample(false);
    if (state.multilayer()) resample_deep_ = resample(true);
  }

  StageKind kind() const override { return StageKind::temporal_splat; }
  uint32_t timed_passes() const override { return 4; }

  // The counting sort, before the initial stage (RestirMethod::record): the forward splats and
  // where they land do not depend on this frame's canonical samples.
  void record_before_initial(const StageFrame& f) override {
    ran_ = f.frame.history_valid;
    moved_ = f.frame.scene_moved;
    changed_ = state_.shared.scene.changed_instances();
    if (!ran_) return;
    // K of this frame (RS-main Eq. 19), as the passes read it from the frame constants.
    partitions_ = time_partitions(f.frame.frame, state_.settings.restir.splats_per_frame);
    if (partitions_ > allocated_partitions_) {
      allocate_records(partitions_);
      for (Pass* p : {project_.get(), project_deep_.get(), insert_.get(), resample_.get(), resample_deep_.get()})
        if (p) p->rebind();
    }
    const uint32_t w = state_.width, h = state_.height;
    timed(f, "splat_project", [&] {
      vkCmdFillBuffer(f.cmd, count_.handle(), 0, VK_WHOLE_SIZE, 0);
      // Every record lands nowhere until its splat lands (domains the list dispatch leaves out included).
      vkCmdFillBuffer(f.cmd, target_.handle(), 0, VK_WHOLE_SIZE, gpu::SPLAT_NONE);
      gpu::compute_barrier(f.cmd);
      project_->dispatch_layers(f.cmd, f.parity, w, h, partitions_);  // the front layer; z: the time partition
      if (project_deep_) project_deep_->dispatch_indirect(f.cmd, f.parity, state_.domain_args.previous(f.parity));
    });
    timed(f, "splat_scan", [&] { scan_->dispatch_1d(f.cmd, f.parity, 1); });
    timed(f, "splat_insert", [&] { insert_->dispatch_layers(f.cmd, f.parity, w, h, state_.layers * partitions_); });
  }

  void record(const StageFrame& f) override {
    if (!ran_) return;
    const uint32_t w = state_.width, h = state_.height;
    timed(f, "splat_resample", [&] {
      resample_->dispatch_2d(f.cmd, f.parity, w, h);
      if (resample_deep_) resample_deep_->dispatch_indirect(f.cmd, f.parity, state_.domain_args.current(f.parity));
    });
  }

  PassDecision decision() const override {
    if (!ran_) return {"temporal", false, "no previous frame yet"};
    return {"temporal", true,
            std::string(state_.spec.backup ? "splat with backup sample" : "splat") + " (counting sort; reprojection + " +
                options::choice_name("shift", state_.settings.restir.shift) + " shift, reverse-splat MIS, bilinear confidence" +
                (partitions_ > 1 ? "; " + std::to_string(partitions_) + " time partitions over the shutter)" : ")") + "; " +
                suffix_decision(state_.settings.restir.suffix, moved_, changed_)};
  }

  std::map<std::string, uint64_t> memory_bytes() const override {
    return {{"splats", splats_.size() + target_.size() + count_.size() + offsets_.size() + list_.size()}};
  }

  void collect(std::span<const uint32_t> c, FrameStats& s) const override {
    using namespace gpu;
    // RS-main statistics of splatting: splats per pixel (mean over pixels is landed / pixels), the
    // fullest pixel; holes (pixels no splat reached) are temporal.no_history. Of the forward splats
    // that did not land, those that fell outside the image and those whose primary hit is hidden
    // now (the visibility test of RS-main 4.1.1); temporal.primary also counts the reverse splats.
    s.reuse["splat.landed"] = c[COUNTER_SPLATS_LANDED];
    s.reuse["splat.max_per_pixel"] = c[COUNTER_SPLATS_MAX];
    s.reuse["splat.partitions"] = ran_ ? partitions_ : 0;  // K time partitions of this frame's shutter
    s.reuse["splat.offscreen"] = c[COUNTER_SPLATS_OFFSCREEN];
    s.reuse["splat.occluded"] = c[COUNTER_SPLATS_OCCLUDED];
    if (state_.spec.backup || state_.deep_backup()) s.reuse["splat.backup_selected"] = c[COUNTER_SPLAT_BACKUP_SELECTED];
    // Suffix replay rays per pass (of temporal.replay_rays): forward splats, and reverse splats with the backup.
    s.reuse["splat_project.replay_rays"] = c[COUNTER_RAYS_REPLAY];
    s.reuse["splat_resample.replay_rays"] = c[COUNTER_RAYS_REPLAY_RESAMPLE];
    if (state_.multilayer()) {
      // ML Table 1: splats into deep domains, hidden splats no depth range held, the restricted
      // queries of the layer assignment; disoccluded front-layer pixels a previous deep domain covered.
      s.reuse["splat.deep"] = c[COUNTER_SPLATS_DEEP];
      s.reuse["splat.no_layer"] = c[COUNTER_SPLATS_NO_LAYER];
      s.reuse["splat.range_rays"] = c[COUNTER_SPLAT_RANGE_RAYS];
      s.reuse["splat.step_rays"] = c[COUNTER_SPLAT_STEP_RAYS];
      s.reuse["domains.disoccluded_covered"] = c[COUNTER_DISOCCLUDED_COVERED];
      // ... of them, by a splat from a previous deep domain, and by the deep backup (both may)
      s.reuse["domains.disoccluded_splatted"] = c[COUNTER_DISOCCLUDED_SPLATTED];
      if (state_.deep_backup()) s.reuse["domains.disoccluded_backup"] = c[COUNTER_DISOCCLUDED_BACKUP];
    }
  }

 private:
  // Records, targets and the list grow with K (multi-splatting, RS-main Eq. 19) the first time a
  // frame's shutter needs it: a session that never opens the shutter keeps one partition.
  void allocate_records(uint32_t partitions) {
    allocated_partitions_ = partitions;
    const auto& ctx = state_.shared.ctx;
    const size_t records = state_.domains * partitions;
    splats_ = device_storage(ctx, sizeof(gpu::SplatRecord) * records, "splats");
    target_ = device_storage(ctx, sizeof(uint32_t) * records, "splat targets");
    list_ = device_storage(ctx, sizeof(uint32_t) * records, "splat list");
  }

  const RestirState& state_;
  gpu::Buffer count_;
  const gpu::Buffer& offsets_;  // RestirState::splat_offsets (the initial stage reads it too)
  gpu::Buffer splats_, target_, list_;  // reallocated in place by allocate_records (the passes then rebind)
  std::unique_ptr<Pass> project_, scan_, insert_, resample_;
  std::unique_ptr<Pass> project_deep_;   // restir-multilayer: the previous frame's active deep domains' list
  std::unique_ptr<Pass> resample_deep_;  // restir-multilayer: this frame's
  uint32_t allocated_partitions_ = 0;
  uint32_t partitions_ = 1;
  bool ran_ = false;
  bool moved_ = false;
  uint32_t changed_ = 0;  // instances that changed since the previous frame
};

}  // namespace

std::unique_ptr<Stage> make_temporal_splat_stage(const RestirState& state) { return std::make_unique<TemporalSplatStage>(state); }

}  // namespace strata::render
