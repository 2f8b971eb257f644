// Stage `temporal-gather` (restir-gather, restir-di): the current pixel-centre hit is backprojected
// into the previous frame, and the reservoir found there is shifted here and resampled with the
// canonical sample (shaders/passes/restir_temporal.comp). With the unbiased MIS the canonical
// sample's reverse shift into the previous frame runs first, in a pass of its own
// (restir_temporal_reverse.comp), which leaves its p-hat-from per pixel for the second: each pass's
// shift is then compiled for one frame only (half the code), and the two compile in parallel.
#include "include/bindings.h"
#include "options/option_table.h"
#include "render/restir/restir_state.h"
#include "render/restir/stages.h"

namespace strata::render {
namespace {

class TemporalGatherStage : public Stage {
 public:
  explicit TemporalGatherStage(const RestirState& state)
      : state_(state),
        unbiased_(state.settings.restir.unbiased),
        // Without the unbiased MIS it is never read (one entry).
        from_q_(device_storage(state.shared.ctx, sizeof(float) * (unbiased_ ? state.pixels : 1), "temporal p-hat from q")),
        pass_(state.shared.ctx, &state.shared.scene, {.lights = true, .history = true}, "restir_temporal",
              resources(Access::read_write, Access::read)) {
    if (unbiased_)
      reverse_ = std::make_unique<Pass>(state.shared.ctx, &state.shared.scene, SceneUse{.lights = true, .history = true},
                                        "restir_temporal_reverse", resources(Access::read, Access::write));
  }
  uint32_t timed_passes() const override { return 1; }
  void record(const StageFrame& f) override {
    ran_ = f.frame.history_valid;
    held_ = f.frame.history_held;
    moved_ = f.frame.scene_moved;
    changed_ = state_.shared.scene.changed_instances();
    if (!ran_) return;
    timed(f, "temporal", [&] {
      if (reverse_) {
        reverse_->dispatch_2d(f.cmd, f.parity, state_.width, state_.height);
        gpu::compute_barrier(f.cmd);
      }
      pass_.dispatch_2d(f.cmd, f.parity, state_.width, state_.height);
    });
  }
  std::map<std::string, uint64_t> memory_bytes() const override {
    if (!unbiased_) return {};
    return {{"temporal_from_q", from_q_.size()}};
  }
  PassDecision decision() const override {
    const RestirOptions& o = state_.settings.restir;
    if (!ran_) return {"temporal", false, no_history_reason(held_)};
    return {"temporal", true,
            "gather, " + options::choice_name("shift", o.shift) + " shift, " + (o.unbiased ? "reverse-shift MIS" : "confidence weights (biased)") + "; " +
                suffix_decision(o.suffix, moved_, changed_)};
  }

 private:
  // `reservoirs`: the canonical reservoirs (read by the reverse pass, resampled by the temporal pass);
  // `from_q`: written by the reverse pass, read by the temporal pass.
  std::vector<PassResource> resources(Access reservoirs, Access from_q) const {
    return restir_resources(state_, storage(BINDING_RESERVOIRS_OUT, reservoirs, state_.work),
                            {history_previous(BINDING_RESERVOIRS_IN, state_.history),
                             history_current(BINDING_PRIMARY, Access::read, state_.visibility),
                             history_previous(BINDING_PRIMARY_PREV, state_.visibility),
                             storage(BINDING_TEMPORAL_FROM_Q, from_q, from_q_)});
  }

  const RestirState& state_;
  bool unbiased_;
  gpu::Buffer from_q_;
  Pass pass_;
  std::unique_ptr<Pass> reverse_;  // unbiased_ only
  bool ran_ = false;
  bool held_ = false;
  bool moved_ = false;
  uint32_t changed_ = 0;  // instances that changed since the previous frame
};

}  // namespace

std::unique_ptr<Stage> make_temporal_gather_stage(const RestirState& state) { return std::make_unique<TemporalGatherStage>(state); }

}  // namespace strata::render
