#include "render/restir/stages.h"

#include "include/bindings.h"
#include "render/restir/restir_state.h"

namespace strata::render {
namespace {

class InitialStage : public Stage {
 public:
  explicit InitialStage(const RestirState& state)
      : state_(state),
        pass_(state.shared.ctx, &state.shared.scene, {.lights = true, .history = false}, "restir_initial",
              restir_resources(state, storage(BINDING_RESERVOIRS_OUT, Access::write, state.work),
                               {history_current(BINDING_PRIMARY, Access::read, state.visibility)})) {}
  StageKind kind() const override { return StageKind::initial; }
  uint32_t timed_passes() const override { return 1; }
  void record(const StageFrame& f) override {
    timed(f, "initial", [&] { pass_.dispatch_2d(f.cmd, f.parity, state_.width, state_.height); });
  }
  PassDecision decision() const override {
    const RestirOptions& o = state_.settings.restir;
    const bool di = state_.spec.direct_lighting || o.direct_lighting;
    std::string paths = di ? "one-bounce paths (ReSTIR DI)" : "paths of up to " + std::to_string(state_.settings.max_depth) + " segments";
    std::string start = state_.spec.fixed_primary ? ", from the pixel's primary hit of the frame" : ", each with its own camera ray";
    return {"initial", true,
            std::to_string(o.initial_candidates) + " candidate path(s), " + std::to_string(o.light_candidates) +
                " light candidate(s) per vertex, " + paths + start};
  }

 private:
  const RestirState& state_;
  Pass pass_;
};

}  // namespace

std::unique_ptr<Stage> make_initial_stage(const RestirState& state) { return std::make_unique<InitialStage>(state); }

}  // namespace strata::render
