#include "render/restir/stages.h"

#include "include/bindings.h"
#include "include/frame_data.h"
#include "render/restir/restir_state.h"

namespace strata::render {
namespace {

// The canonical samples: the image dispatch (the front layer) and, for restir-multilayer, the same
// shader over the compacted list of active deep domains (SPEC_DOMAIN_LIST, an indirect dispatch).
class InitialStage : public Stage {
 public:
  explicit InitialStage(const RestirState& state)
      : state_(state), pass_(state.shared.ctx, &state.shared.scene, {.lights = true, .history = false}, "restir_initial", resources(), spec(false)) {
    if (state.multilayer())
      deep_ = std::make_unique<Pass>(state.shared.ctx, &state.shared.scene, SceneUse{.lights = true, .history = false}, "restir_initial",
                                     resources(), spec(true));
  }
  uint32_t timed_passes() const override { return 1; }
  void record(const StageFrame& f) override {
    timed(f, "initial", [&] {
      pass_.dispatch_2d(f.cmd, f.parity, state_.width, state_.height);
      if (deep_) deep_->dispatch_indirect(f.cmd, f.parity, state_.domain_args.current(f.parity));
    });
  }
  void collect(std::span<const uint32_t> c, FrameStats& s) const override {
    if (boost()) s.reuse["initial.disocclusion_boosted"] = c[gpu::COUNTER_DISOCCLUSION_BOOSTED];  // ML Fig. 9 "more initial spp"
  }
  PassDecision decision() const override {
    const RestirOptions& o = state_.settings.restir;
    const bool di = state_.spec.direct_lighting || o.direct_lighting;
    std::string paths = di ? "one-bounce paths (ReSTIR DI)" : "paths of up to " + std::to_string(state_.settings.max_depth) + " segments";
    std::string start = state_.spec.fixed_primary ? ", from the pixel's primary hit of the frame" : ", each with its own camera ray";
    return {"initial", true,
            std::to_string(o.initial_candidates) + " candidate path(s)" +
                (boost() ? " (" + std::to_string(candidates()) + (deep_ ? " where a disoccluded pixel got no splat)" : " where no splat landed)")
                         : std::string()) + ", " + std::to_string(o.light_candidates) +
                " light candidate(s) per vertex, " + paths + start +
                (deep_ ? "; and one canonical sample per active deep domain (ML Eq. 3-4: the first hit within its depth range, hidden from the camera)"
                       : "")};
  }

 private:
  std::vector<PassResource> resources() const {
    return restir_resources(state_, storage(BINDING_RESERVOIRS_OUT, Access::write, state_.work),
                            {history_current(BINDING_PRIMARY, Access::read, state_.visibility),
                             history_current(BINDING_DOMAINS, Access::read, state_.domain_ranges),
                             history_current(BINDING_DOMAIN_LIST, Access::read, state_.domain_list),
                             history_current(BINDING_DOMAIN_ARGS, Access::read, state_.domain_args),
                             storage(BINDING_SPLAT_OFFSETS, Access::read, state_.splat_offsets)});
  }
  bool boost() const { return state_.splat_sort() && candidates() > 0; }
  uint32_t candidates() const { return state_.settings.restir.disocclusion_candidates(state_.spec, state_.layers); }
  std::vector<gpu::SpecConstant> spec(bool deep) const {
    return {{SPEC_DOMAIN_LIST, deep ? VK_TRUE : VK_FALSE}, {SPEC_LAYER_STEPPING, state_.layer_stepping() ? VK_TRUE : VK_FALSE}};
  }

  const RestirState& state_;
  Pass pass_;
  std::unique_ptr<Pass> deep_;  // restir-multilayer: the active deep domains' list
};

}  // namespace

std::unique_ptr<Stage> make_initial_stage(const RestirState& state) { return std::make_unique<InitialStage>(state); }

}  // namespace strata::render
