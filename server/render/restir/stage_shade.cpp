// Stage `shade`: each pixel's estimate from its last resampling (the expectation of f(Y) W over
// that pass's candidates, restir/gris.h) plus what its camera rays see directly, added to the
// image (shaders/passes/restir_shade.comp).
#include "include/bindings.h"
#include "render/restir/restir_state.h"
#include "render/restir/stages.h"

namespace strata::render {
namespace {

class ShadeStage : public Stage {
 public:
  explicit ShadeStage(const RestirState& state)
      : state_(state),
        pass_(state.shared.ctx, nullptr, {}, "restir_shade",
              {uniform(BINDING_FRAME, state.shared.constants), uniform(BINDING_RESTIR, state.constants),
               storage(BINDING_COUNTERS, Access::read_write, state.shared.counters),
               storage(BINDING_CONTRIBUTION, Access::read_write, state.contribution),
               storage(BINDING_ACCUM, Access::read_write, state.shared.accum),
               history_current(BINDING_DOMAINS, Access::read, state.domain_ranges)}) {}
  uint32_t timed_passes() const override { return 1; }
  void record(const StageFrame& f) override {
    timed(f, "shade", [&] { pass_.dispatch_2d(f.cmd, f.parity, state_.width, state_.height); });
  }
  PassDecision decision() const override { return {"shade", true, "sum of w f / p-hat over the last resampling's candidates"}; }

 private:
  const RestirState& state_;
  Pass pass_;
};

}  // namespace

std::unique_ptr<Stage> make_shade_stage(const RestirState& state) { return std::make_unique<ShadeStage>(state); }

}  // namespace strata::render
