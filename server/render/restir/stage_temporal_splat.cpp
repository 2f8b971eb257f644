// Stage `temporal-splat` (restir-splat; RS-main 4.1) and, with the method's `backup`,
// `temporal-splat-backup` (restir-splat-backup; RS-main 4.2): instead of gathering the backprojected
// previous pixel's reservoir, every previous reservoir was splatted forward into the pixel its
// primary hit lands in now and sorted by pixel (the splat sort stage, render/restir/splat_sort.h);
// this stage resamples, per current pixel, the canonical sample with the splats that landed there
// (and the backup sample, shifted from the backprojected previous pixel):
//   splat_resample  GRIS of the canonical sample and the landed splats; work -> work
// restir-multilayer (ML 4.1, 4.2): a second resampling dispatch runs over this frame's compacted
// list of active deep domains.
#include "include/bindings.h"
#include "include/frame_data.h"
#include "options/option_table.h"
#include "render/restir/restir_state.h"
#include "render/restir/splat_sort.h"
#include "render/restir/stages.h"

namespace strata::render {
namespace {

class TemporalSplatStage : public Stage {
 public:
  TemporalSplatStage(const RestirState& state, const SplatSortStage& sort) : state_(state), sorted_(sort.lists()) {
    const GpuScene* scene = &state.shared.scene;
    const SceneUse with_history{.lights = true, .history = true};  // lights: the suffix replay's NEE end
    const uint32_t stepping = state.layer_stepping() ? VK_TRUE : VK_FALSE;  // layers by rank (restir/layers.glsl)
    auto resample = [&](bool deep) {
      return std::make_unique<Pass>(state.shared.ctx, scene, with_history, "restir_splat_resample",
                                    restir_resources(state, storage(BINDING_RESERVOIRS_OUT, Access::read_write, state.work),
                                                     {history_previous(BINDING_RESERVOIRS_IN, state.history),
                                                      storage(BINDING_SPLATS, Access::read, sorted_.splats),
                                                      storage(BINDING_SPLAT_OFFSETS, Access::read, state.splat_offsets),
                                                      storage(BINDING_SPLAT_LIST, Access::read, sorted_.list),
                                                      history_current(BINDING_PRIMARY, Access::read, state.visibility),
                                                      // read_write: the front layer's DOMAIN_COVERED flag
                                                      history_current(BINDING_DOMAINS, Access::read_write, state.domain_ranges),
                                                      history_previous(BINDING_DOMAINS_PREV, state.domain_ranges),
                                                      history_current(BINDING_DOMAIN_LIST, Access::read, state.domain_list),
                                                      history_current(BINDING_DOMAIN_ARGS, Access::read, state.domain_args)}),
                                    std::vector<gpu::SpecConstant>{{SPEC_DOMAIN_LIST, deep ? VK_TRUE : VK_FALSE}, {SPEC_LAYER_STEPPING, stepping}});
    };
    resample_ = resample(false);
    if (state.multilayer()) resample_deep_ = resample(true);
    bound_generation_ = sorted_.generation;
  }

  uint32_t timed_passes() const override { return 1; }

  // The sort's lists, work (canonical samples), visibility.current -> work.
  void record(const StageFrame& f) override {
    moved_ = f.frame.scene_moved;
    changed_ = state_.shared.scene.changed_instances();
    if (!sorted_.ran) return;
    if (bound_generation_ != sorted_.generation) {  // the sort grew its records for more time partitions
      for (Pass* p : {resample_.get(), resample_deep_.get()})
        if (p) p->rebind();
      bound_generation_ = sorted_.generation;
    }
    timed(f, "splat_resample", [&] {
      resample_->dispatch_2d(f.cmd, f.parity, state_.width, state_.height);
      if (resample_deep_) resample_deep_->dispatch_indirect(f.cmd, f.parity, state_.domain_args.current(f.parity));
    });
  }

  PassDecision decision() const override {
    if (!sorted_.ran) return {"temporal", false, no_history_reason(sorted_.held)};
    const uint32_t k = sorted_.partitions;
    return {"temporal", true,
            std::string(state_.spec.backup ? "splat with backup sample" : "splat") + " (counting sort; reprojection + " +
                options::choice_name("shift", state_.settings.restir.shift) + " shift, reverse-splat MIS, bilinear confidence" +
                (k > 1 ? "; " + std::to_string(k) + " time partitions over the shutter)" : ")") + "; " +
                suffix_decision(state_.settings.restir.suffix, moved_, changed_)};
  }

  void collect(std::span<const uint32_t> c, FrameStats& s) const override {
    using namespace gpu;
    // RS-main statistics of splatting: splats per pixel (mean over pixels is landed / pixels), the
    // fullest pixel; holes (pixels no splat reached) are temporal.no_history. Of the forward splats
    // that did not land, those that fell outside the image and those whose primary hit is hidden
    // now (the visibility test of RS-main 4.1.1); temporal.primary also counts the reverse splats.
    s.reuse["splat.landed"] = c[COUNTER_SPLATS_LANDED];
    s.reuse["splat.max_per_pixel"] = c[COUNTER_SPLATS_MAX];
    s.reuse["splat.partitions"] = sorted_.ran ? sorted_.partitions : 0;  // K time partitions of this frame's shutter
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
  const RestirState& state_;
  const SplatLists& sorted_;  // the splat sort stage's output
  std::unique_ptr<Pass> resample_;
  std::unique_ptr<Pass> resample_deep_;  // restir-multilayer: this frame's active deep domains' list
  uint32_t bound_generation_ = 0;
  bool moved_ = false;
  uint32_t changed_ = 0;  // instances that changed since the previous frame
};

}  // namespace

std::unique_ptr<Stage> make_temporal_splat_stage(const RestirState& state, const SplatSortStage& sort) {
  return std::make_unique<TemporalSplatStage>(state, sort);
}

}  // namespace strata::render
