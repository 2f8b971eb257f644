// Stage `domain_init` (restir-multilayer; ML 4.3, Sec. 5; docs/ARCHITECTURE.md, "Pixel layers"):
// the pixel-layer domains of this frame, before any sample is drawn:
//   domain_propagate  per previous domain that propagates (the front layer's, then the previous
//                     frame's list of active deep domains): its representative hit moved into this
//                     frame, its new layer counted along the camera ray, a mark with its occluder
//   domain_build      per pixel: the representative hits of the deep layers it needs (the centre
//                     ray walked on), the occluder check, the depth ranges of all its layers
//   domain_fill       per pixel: hole filling, the silhouette band (dormant deep domains), the
//                     compacted lists of active and dormant deep domains (and the indirect
//                     dispatches' workgroups), inactive deep reservoirs emptied
// Reads the previous frame's domain state (domain_ranges, visibility, domain_list and domain_args:
// previous) and writes this frame's (their current halves; visibility: the deep entries).
#include "include/bindings.h"
#include "include/frame_data.h"
#include "render/restir/restir_state.h"
#include "render/restir/stages.h"
#include "restir/layer_data.h"

namespace strata::render {
namespace {

class DomainInitStage : public Stage {
 public:
  explicit DomainInitStage(const RestirState& state) : state_(state) {
    const auto& ctx = state.shared.ctx;
    const GpuScene* scene = &state.shared.scene;
    auto common = [&] {
      return std::vector<PassResource>{uniform(BINDING_FRAME, state.shared.constants), uniform(BINDING_RESTIR, state.constants),
                                       storage(BINDING_COUNTERS, Access::read_write, state.shared.counters)};
    };
    auto propagate = [&](bool list, bool dormant) {
      auto r = common();
      r.push_back(history_previous(BINDING_PRIMARY_PREV, state.visibility));
      r.push_back(history_current(BINDING_PRIMARY, Access::read, state.visibility));  // this frame's centre hits
      r.push_back(history_previous(BINDING_DOMAINS_PREV, state.domain_ranges));
      r.push_back(storage(BINDING_DOMAIN_MARKS, Access::read_write, state.domain_marks));
      r.push_back(history_previous(BINDING_DOMAIN_LIST_PREV, state.domain_list));
      r.push_back(history_previous(BINDING_DOMAIN_ARGS_PREV, state.domain_args));
      return std::make_unique<Pass>(ctx, scene, SceneUse{.lights = false, .history = true}, "domain_propagate", std::move(r),
                                    std::vector<gpu::SpecConstant>{{SPEC_DOMAIN_LIST, list ? VK_TRUE : VK_FALSE},
                                                                   {SPEC_DORMANT_LIST, dormant ? VK_TRUE : VK_FALSE}});
    };
    propagate_front_ = propagate(false, false);
    propagate_deep_ = propagate(true, false);
    if (state.dormancy()) propagate_dormant_ = propagate(true, true);
    auto build = common();
    build.push_back(history_current(BINDING_PRIMARY, Access::read_write, state.visibility));
    build.push_back(history_current(BINDING_DOMAINS, Access::write, state.domain_ranges));
    build.push_back(storage(BINDING_DOMAIN_MARKS, Access::read, state.domain_marks));
    build.push_back(history_previous(BINDING_PRIMARY_PREV, state.visibility));  // the previous centre hits: disocclusion
    build.push_back(history_previous(BINDING_DOMAINS_PREV, state.domain_ranges));  // ... and the domains that held it
    build_ = std::make_unique<Pass>(ctx, scene, SceneUse{.lights = false, .history = true}, "domain_build", std::move(build));
    auto fill = common();
    fill.push_back(storage(BINDING_RESERVOIRS_OUT, Access::write, state.work));
    fill.push_back(history_current(BINDING_DOMAINS, Access::read_write, state.domain_ranges));
    fill.push_back(history_current(BINDING_DOMAIN_LIST, Access::write, state.domain_list));
    fill.push_back(history_current(BINDING_DOMAIN_ARGS, Access::read_write, state.domain_args));
    fill_ = std::make_unique<Pass>(ctx, nullptr, SceneUse{}, "domain_fill", std::move(fill));
  }

  uint32_t timed_passes() const override { return 1; }

  void record(const StageFrame& f) override {
    // layer_mode uniform keeps every layer active: nothing to propagate.
    propagated_ = f.frame.history_valid && state_.settings.restir.layer_mode != LayerMode::uniform;
    timed(f, "domain_init", [&] {
      vkCmdFillBuffer(f.cmd, state_.domain_marks.handle(), 0, VK_WHOLE_SIZE, gpu::OCCLUDER_NONE);  // no marks
      const gpu::GpuDomainArgs empty[2] = {{0, 1, 1, 0}, {0, 1, 1, 0}};  // no workgroups yet; y = z = 1; length 0
      vkCmdUpdateBuffer(f.cmd, state_.domain_args.current(f.parity).handle(), 0, sizeof empty, empty);
      gpu::compute_barrier(f.cmd);
      if (propagated_) {
        propagate_front_->dispatch_2d(f.cmd, f.parity, state_.width, state_.height);
        propagate_deep_->dispatch_indirect(f.cmd, f.parity, state_.domain_args.previous(f.parity));
        if (propagate_dormant_)
          propagate_dormant_->dispatch_indirect(f.cmd, f.parity, state_.domain_args.previous(f.parity),
                                                gpu::DOMAIN_ARGS_DORMANT * sizeof(gpu::GpuDomainArgs));
        gpu::compute_barrier(f.cmd);
      }
      build_->dispatch_2d(f.cmd, f.parity, state_.width, state_.height);
      gpu::compute_barrier(f.cmd);
      fill_->dispatch_2d(f.cmd, f.parity, state_.width, state_.height);
    });
  }

  PassDecision decision() const override {
    const RestirOptions& o = state_.settings.restir;
    std::string mode = o.layer_mode == LayerMode::uniform ? "uniform: every layer of every pixel active (ML Fig. 5 validation)"
                       : o.layer_mode == LayerMode::no_depth_ranges
                           ? "active domains, layers found by stepping rays (ML Table 1 'w/o ranges')"
                           : "active domains propagated by representative hits, occluder check, depth ranges e = 0.01";
    return {"domain_init", true,
            std::to_string(state_.layers) + " layers (" + state_.layers_reason + "); " + mode +
                (o.layer_mode == LayerMode::uniform ? std::string()
                                           : "; hole filling radius " + std::to_string(o.hole_fill_radius) + " px" +
                                                 dormancy_reason()) +
                (propagated_ || o.layer_mode == LayerMode::uniform ? "" : "; no previous frame: front layer only")};
  }

  void collect(std::span<const uint32_t> c, FrameStats& s) const override {
    using namespace gpu;
    // ML Table 1: active domains by layer, deep domains (propagated / filled), what a uniform
    // scheme keeps, the rays the domains cost.
    uint64_t deep = 0;
    for (uint32_t i = 0; i < state_.layers; ++i) {
      s.reuse["domains.active_layer_" + std::to_string(i)] = c[COUNTER_DOMAINS_ACTIVE + i];
      if (i > 0) deep += c[COUNTER_DOMAINS_ACTIVE + i];
    }
    s.reuse["domains.deep"] = deep;
    s.reuse["domains.propagated"] = c[COUNTER_DOMAINS_PROPAGATED];
    s.reuse["domains.filled"] = c[COUNTER_DOMAINS_FILLED];
    // ... and propagated ones the reveal prediction or the silhouette band left dormant (tracked, not
    // sampled, not in deep)
    if (state_.dormancy()) s.reuse["domains.dormant"] = c[COUNTER_DOMAINS_DORMANT];
    s.reuse["domains.occluder_refused"] = c[COUNTER_DOMAINS_OCCLUDER];
    s.reuse["domains.uniform_deep"] = c[COUNTER_DOMAINS_UNIFORM];
    s.reuse["domains.disoccluded"] = c[COUNTER_DISOCCLUDED];  // front-layer hits hidden from the previous camera
    // ... of them, hits an active previous deep domain held (in its depth range, at the previous
    // pixel the hit falls in): the activation's coverage, whether or not a splat then lands
    s.reuse["domains.disoccluded_held"] = c[COUNTER_DISOCCLUDED_HELD];
    s.rays_traced["domain_init"] = c[COUNTER_RAYS_DOMAIN_INIT];
  }

 private:
  // Which deep domains sample (domain_fill.comp), as the decision says it.
  std::string dormancy_reason() const {
    const uint32_t lookahead = state_.reveal_lookahead(), band = state_.silhouette_band();
    std::string r;
    if (lookahead > 0)
      r = "; deep domains sample when predicted to be uncovered within " + std::to_string(lookahead) + " frame" + (lookahead == 1 ? "" : "s") +
          " (their motion against the front layer over the last frame), dormant otherwise";
    if (band > 0)
      r += std::string(lookahead > 0 ? "; without a prediction, those" : "; deep domains") + " beyond " + std::to_string(band) +
           " px of a silhouette dormant";
    return r;
  }

  const RestirState& state_;
  std::unique_ptr<Pass> propagate_front_, propagate_deep_, propagate_dormant_, build_, fill_;
  bool propagated_ = false;
};

}  // namespace

std::unique_ptr<Stage> make_domain_init_stage(const RestirState& state) { return std::make_unique<DomainInitStage>(state); }

}  // namespace strata::render
