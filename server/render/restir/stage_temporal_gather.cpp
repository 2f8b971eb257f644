// Stage `temporal-gather` (restir-gather, restir-di): the current pixel-centre hit is backprojected
// into the previous frame, and the reservoir found there is shifted here and resampled with the
// canonical sample (shaders/passes/restir_temporal.comp).
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
        pass_(state.shared.ctx, &state.shared.scene, {.lights = true, .history = true}, "restir_temporal",
              restir_resources(state, storage(BINDING_RESERVOIRS_OUT, Access::read_write, state.work),
                               {history_previous(BINDING_RESERVOIRS_IN, state.history),
                                history_current(BINDING_PRIMARY, Access::read, state.visibility),
                                history_previous(BINDING_PRIMARY_PREV, state.visibility)})) {}
  uint32_t timed_passes() const override { return 1; }
  void record(const StageFrame& f) override {
    ran_ = f.frame.history_valid;
    held_ = f.frame.history_held;
    moved_ = f.frame.scene_moved;
    changed_ = state_.shared.scene.changed_instances();
    if (!ran_) return;
    timed(f, "temporal", [&] { pass_.dispatch_2d(f.cmd, f.parity, state_.width, state_.height); });
  }
  PassDecision decision() const override {
    const RestirOptions& o = state_.settings.restir;
    if (!ran_) return {"temporal", false, no_history_reason(held_)};
    return {"temporal", true,
            "gather, " + options::choice_name("shift", o.shift) + " shift, " + (o.unbiased ? "reverse-shift MIS" : "confidence weights (biased)") + "; " +
                suffix_decision(o.suffix, moved_, changed_)};
  }

 private:
  const RestirState& state_;
  Pass pass_;
  bool ran_ = false;
  bool held_ = false;
  bool moved_ = false;
  uint32_t changed_ = 0;  // instances that changed since the previous frame
};

}  // namespace

std::unique_ptr<Stage> make_temporal_gather_stage(const RestirState& state) { return std::make_unique<TemporalGatherStage>(state); }

}  // namespace strata::render
