// Stage `spatial`: neighbours in a disk of spatial_radius pixels whose pixel-centre surfaces (the
// primary stage's visibility buffer) resemble the pixel's, shifted into each pixel and resampled
// with its reservoir (shaders/passes/restir_spatial.comp); the result is the frame's final
// reservoir, written into the history's current slot. Pixels without history take
// disocclusion_spatial_neighbors; when that differs from spatial_neighbors, the image dispatch only
// lists them and an indirect dispatch runs the list densely (no SIMD group waits on one such pixel).
#include <cstdio>

#include "include/bindings.h"
#include "restir/restir_limits.h"
#include "render/restir/restir_state.h"
#include "render/restir/stages.h"

namespace strata::render {
namespace {

// Whether pixels without history take another neighbour count than the others.
bool compacts(const RestirOptions& o) {
  return o.disocclusion_spatial_neighbors != 0 && o.disocclusion_spatial_neighbors != o.spatial_neighbors;
}

class SpatialStage : public Stage {
 public:
  explicit SpatialStage(const RestirState& state)
      : state_(state),
        compact_(compacts(state.settings.restir)),
        // The list holds one entry per pixel; without compaction it is never written (one entry).
        list_(device_storage(state.shared.ctx, sizeof(uint32_t) * (compact_ ? state.domains : 1), "spatial list")),
        args_(state.shared.ctx, sizeof(uint32_t) * 4, gpu::k_indirect_usage, gpu::Memory::Device, "spatial list arguments"),
        pass_(state.shared.ctx, &state.shared.scene, {.lights = false, .history = false}, "restir_spatial", resources(),
              {{SPEC_SPATIAL_LIST, VK_FALSE}, {SPEC_SPATIAL_COMPACT, compact_ ? VK_TRUE : VK_FALSE}}) {
    if (compact_)
      list_pass_ = std::make_unique<Pass>(state.shared.ctx, &state.shared.scene, SceneUse{}, "restir_spatial", resources(),
                                          std::vector<gpu::SpecConstant>{{SPEC_SPATIAL_LIST, VK_TRUE}, {SPEC_SPATIAL_COMPACT, VK_TRUE}});
  }
  StageKind kind() const override { return StageKind::spatial; }
  uint32_t timed_passes() const override { return 1; }
  void record(const StageFrame& f) override {
    timed(f, "spatial", [&] {
      if (compact_) {
        const uint32_t empty[4] = {0, 1, 1, 0};  // no workgroups yet; y = z = 1; length 0
        vkCmdUpdateBuffer(f.cmd, args_.handle(), 0, sizeof empty, empty);
        gpu::compute_barrier(f.cmd);
      }
      pass_.dispatch_2d(f.cmd, f.parity, state_.width, state_.height);
      if (compact_) {
        gpu::compute_barrier(f.cmd);
        list_pass_->dispatch_indirect(f.cmd, f.parity, args_);
      }
    });
  }
  std::map<std::string, uint64_t> memory_bytes() const override {
    return compact_ ? std::map<std::string, uint64_t>{{"spatial_list", list_.size() + args_.size()}} : std::map<std::string, uint64_t>{};
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
  std::vector<PassResource> resources() const {
    return restir_resources(state_, history_current(BINDING_RESERVOIRS_OUT, Access::write, state_.history),
                            {storage(BINDING_RESERVOIRS_IN, Access::read, state_.work),
                             history_current(BINDING_PRIMARY, Access::read, state_.visibility),
                             storage(BINDING_SPATIAL_LIST, Access::read_write, list_),
                             storage(BINDING_SPATIAL_ARGS, Access::read_write, args_)});
  }

  const RestirState& state_;
  bool compact_;
  gpu::Buffer list_;
  gpu::Buffer args_;
  Pass pass_;
  std::unique_ptr<Pass> list_pass_;  // the list of pixels without history (compact_ only)
};

}  // namespace

std::unique_ptr<Stage> make_spatial_stage(const RestirState& state) { return std::make_unique<SpatialStage>(state); }

}  // namespace strata::render
