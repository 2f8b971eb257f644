// Stage `primary`: the visibility buffer of this frame (shaders/passes/primary.comp): one camera ray
// per pixel (its camera sample with fixed primary vertices, else the pixel centre), traced once,
// into RestirState::visibility's current slot.
#include "include/bindings.h"
#include "render/restir/restir_state.h"
#include "render/restir/stages.h"

namespace strata::render {
namespace {

class PrimaryStage : public Stage {
 public:
  explicit PrimaryStage(const RestirState& state)
      : state_(state),
        pass_(state.shared.ctx, &state.shared.scene, {.lights = false, .history = false}, "primary",
              {uniform(BINDING_FRAME, state.shared.constants),
               history_current(BINDING_PRIMARY, Access::write, state.visibility),
               history_current(BINDING_PRIMARY_MATERIAL, Access::write, state.primary_material)}) {}
  uint32_t timed_passes() const override { return 1; }
  void record(const StageFrame& f) override {
    timed(f, "primary", [&] { pass_.dispatch_2d(f.cmd, f.parity, state_.width, state_.height); });
  }
  PassDecision decision() const override {
    if (state_.spec.fixed_primary)
      return {"primary", true, "each pixel's camera sample of the frame: its domain's primary vertex, where its paths and every shift into it start"};
    return {"primary", true, "pixel-centre hits for the temporal stage and the spatial neighbour filter"};
  }
  void collect(std::span<const uint32_t>, FrameStats& s) const override {
    s.rays_traced["primary"] = uint64_t(state_.width) * state_.height;  // one ray per pixel
  }

 private:
  const RestirState& state_;
  Pass pass_;
};

}  // namespace

std::unique_ptr<Stage> make_primary_stage(const RestirState& state) { return std::make_unique<PrimaryStage>(state); }

}  // namespace strata::render
