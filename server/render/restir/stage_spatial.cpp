// Stage `spatial`: neighbours in a disk of spatial_radius pixels whose pixel-centre surfaces (the
// primary stage's visibility buffer) resemble the pixel's, shifted into each pixel and resampled
// with its reservoir (shaders/passes/restir_spatial.comp); the result is the frame's final
// reservoir, written into the history's current slot.
#include <cstdio>

#include "include/bindings.h"
#include "restir/restir_limits.h"
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
                               {storage(BINDING_RESERVOIRS_IN, Access::read, state.work),
                                history_current(BINDING_PRIMARY, Access::read, state.visibility)})) {}
  StageKind kind() const override { return StageKind::spatial; }
  uint32_t timed_passes() const override { return 1; }
  void record(const StageFrame& f) override {
    timed(f, "spatial", [&] { pass_.dispatch_2d(f.cmd, f.parity, state_.width, state_.height); });
  }
  PassDecision decision() const override {
    const RestirOptions& o = state_.settings.restir;
    char radius[160];
    const float px = o.spatial_radius_pixels(state_.height);
    if (o.spatial_radius > 0.0f) std::snprintf(radius, sizeof radius, "radius %.1f px (requested)", px);
    else
      std::snprintf(radius, sizeof radius, "radius %.1f px (%.1f%% of the %u px image height, at least %.0f px: the references' 20-32 px at 1080p)",
                    px, 100.0f * RestirOptions::spatial_radius_fraction, state_.height, RestirOptions::spatial_radius_floor);
    return {"spatial", true,
            std::to_string(o.spatial_neighbors) + " neighbour(s) in one round, " + radius + ", " + o.mis +
                " MIS; candidates whose pixel-centre surface differs (normal > 25 deg, depth > 10%, material kind) are "
                "refused from the primary pass before any sample is read, " + std::to_string(gpu::RESTIR_SPATIAL_TRIES) +
                " tries per neighbour; " +
                (o.spatial_neighbors == RestirOptions{}.spatial_neighbors
                     ? std::string("the default count: at 256x256 the smallest that lowered RelMSE against temporal-only "
                                   "reuse on every built-in scene, over frames 0..3 and on frame 3 (docs/BENCHMARKS.md)")
                     : std::string("count requested"))};
  }

 private:
  const RestirState& state_;
  Pass pass_;
};

}  // namespace

std::unique_ptr<Stage> make_spatial_stage(const RestirState& state) { return std::make_unique<SpatialStage>(state); }

}  // namespace strata::render
