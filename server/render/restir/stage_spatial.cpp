// Stage `spatial`: neighbours in a disk of spatial_radius pixels, shifted into each pixel and
// resampled with its reservoir (shaders/passes/restir_spatial.comp); the result is the frame's
// final reservoir, written into the history's current slot.
#include "include/bindings.h"
#include "render/restir/restir_state.h"
#include "render/restir/stages.h"

namespace strata::render {
namespace {

class SpatialStage : public Stage {
 public:
  explicit SpatialStage(const RestirState& state)
      : state_(state),
        pass_(state.shared.ctx, &state.shared.scene, {.lights = false, .history = false}, "restir_spatial",
              restir_resources(state, history_current(BINDING_RESERVOIRS_OUT, Access::write, state.history),
                               {storage(BINDING_RESERVOIRS_IN, Access::read, state.work)})) {}
  StageKind kind() const override { return StageKind::spatial; }
  uint32_t timed_passes() const override { return 1; }
  void record(const StageFrame& f) override {
    timed(f, "spatial", [&] { pass_.dispatch_2d(f.cmd, f.parity, state_.width, state_.height); });
  }
  PassDecision decision() const override {
    const RestirOptions& o = state_.settings.restir;
    return {"spatial", true, std::to_string(o.spatial_neighbors) + " neighbour(s), " + o.mis + " MIS"};
  }

 private:
  const RestirState& state_;
  Pass pass_;
};

}  // namespace

std::unique_ptr<Stage> make_spatial_stage(const RestirState& state) { return std::make_unique<SpatialStage>(state); }

}  // namespace strata::render
