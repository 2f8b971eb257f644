// Stage `spatial`: neighbours in a disk of spatial_radius pixels whose pixel-centre surfaces (the
// primary stage's visibility buffer) resemble the pixel's, shifted into each pixel and resampled
// with its reservoir (shaders/passes/restir_spatial.comp); the result is the frame's final
// reservoir, written into the history's current slot. With pairwise MIS the first two neighbours
// are the frame's pair (restir/spatial_pairs.glsl), shifted both ways once by a pass before
// (restir_spatial_pairs.comp). Pixels without history take disocclusion_spatial_neighbors; the
// pixels that draw neighbours at random (those, or with pairs every pixel whose pair leaves its
// count short) are only listed by the image dispatch and an indirect dispatch of the same pipeline
// runs the list densely (no SIMD group waits on one such pixel); a push constant tells the two
// apart, so that one pipeline is compiled for both.
#include <algorithm>
#include <cstdio>

#include "include/bindings.h"
#include "options/option_table.h"
#include "restir/restir_limits.h"
#include "restir/spatial_pair_data.h"
#include "render/restir/restir_state.h"
#include "render/restir/stages.h"

namespace strata::render {
namespace {

// The frame's pair offsets: enough pairs for spatial_neighbors (restir/spatial_pairs.glsl). Paired
// neighbours need pairwise MIS (the balance heuristic shifts every neighbour's sample into every
// other neighbour's domain, which a pair does not provide), so balance has none.
uint32_t pair_offsets(const RestirOptions& o) {
  if (o.mis != Mis::pairwise) return 0;
  return std::min((o.spatial_neighbors + 1) / 2, gpu::SPATIAL_MAX_PAIR_OFFSETS);
}
bool pairs(const RestirOptions& o) { return pair_offsets(o) > 0; }

// Whether some pixels draw neighbours at random while others do not: pixels without history take
// another neighbour count than the others, or the pair leaves some pixels short.
bool compacts(const RestirOptions& o) {
  return pairs(o) || (o.disocclusion_spatial_neighbors != 0 && o.disocclusion_spatial_neighbors != o.spatial_neighbors);
}

std::vector<gpu::SpecConstant> spatial_spec(bool compact, uint32_t pair_offsets) {
  return {{SPEC_SPATIAL_COMPACT, compact ? VK_TRUE : VK_FALSE},
          {SPEC_SPATIAL_PAIRS, pair_offsets}};
}

class SpatialStage : public Stage {
 public:
  explicit SpatialStage(const RestirState& state)
      : state_(state),
        pair_offsets_(pair_offsets(state.settings.restir)),
        pairs_(pair_offsets_ > 0),
        compact_(compacts(state.settings.restir)),
        // The list holds one entry per pixel; without compaction it is never written (one entry).
        list_(device_storage(state.shared.ctx, sizeof(uint32_t) * (compact_ ? state.pixels : 1), "spatial list")),
        args_(state.shared.ctx, sizeof(uint32_t) * 4, gpu::k_indirect_usage, gpu::Memory::Device, "spatial list arguments"),
        // Two records per pixel and pair offset; without pairs it is never read (one record).
        pair_shifts_(device_storage(state.shared.ctx, sizeof(gpu::PairShift) * (pairs_ ? 2 * pair_offsets_ * state.pixels : 1),
                                    "spatial pair shifts")),
        pass_(state.shared.ctx, &state.shared.scene, SceneUse{.shifts = true}, "restir_spatial", resources(Access::read),
              spatial_spec(compact_, pair_offsets_), sizeof(gpu::SpatialDispatch)) {
    if (pairs_)
      pairs_pass_ = std::make_unique<Pass>(state.shared.ctx, &state.shared.scene, SceneUse{.shifts = true}, "restir_spatial_pairs",
                                           resources(Access::write), spatial_spec(false, pair_offsets_));
  }
  uint32_t timed_passes() const override { return 1; }
  void record(const StageFrame& f) override {
    timed(f, "spatial", [&] {
      if (compact_) {
        const uint32_t empty[4] = {0, 1, 1, 0};  // no workgroups yet; y = z = 1; length 0
        vkCmdUpdateBuffer(f.cmd, args_.handle(), 0, sizeof empty, empty);
        gpu::compute_barrier(f.cmd);
      }
      if (pairs_) {
        pairs_pass_->dispatch_2d(f.cmd, f.parity, state_.width, state_.height);
        gpu::compute_barrier(f.cmd);
      }
      const gpu::SpatialDispatch image{0}, list{1};
      pass_.dispatch_2d(f.cmd, f.parity, state_.width, state_.height, &image);
      if (compact_) {
        gpu::compute_barrier(f.cmd);
        pass_.dispatch_indirect(f.cmd, f.parity, args_, 0, &list);
      }
    });
  }
  std::map<std::string, uint64_t> memory_bytes() const override {
    std::map<std::string, uint64_t> m;
    if (compact_) m["spatial_list"] = list_.size() + args_.size();
    if (pairs_) m["spatial_pairs"] = pair_shifts_.size();
    return m;
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
            std::to_string(o.spatial_neighbors) + " neighbour(s) in one round, " + radius + ", " + options::choice_name("mis", o.mis) + " MIS" +
                (pairs_ ? "; the first are the frame's pairs (i + o and i - o for " + std::to_string(pair_offsets_) +
                              " offset(s) o drawn per frame), each pair's shifts made once for both pixels"
                        : std::string()) +
                "; candidates whose pixel-centre surface differs (normal > 25 deg, depth > 10%, material kind) are "
                "refused from the primary pass before any sample is read, " + std::to_string(gpu::RESTIR_SPATIAL_TRIES) +
                " tries per neighbour; " +
                (o.spatial_neighbors == RestirOptions{}.spatial_neighbors
                     ? std::string("the default count: at 256x256 the smallest that lowered RelMSE against temporal-only "
                                   "reuse on every built-in scene, over frames 0..3 and on frame 3 (docs/BENCHMARKS.md)")
                     : std::string("count requested"))};
  }

 private:
  // The resampling pass writes the final reservoirs and reads the pair shifts; the pairs pass
  // writes the pair shifts (its reservoir output binding is declared by restir_pass.glsl, unused).
  std::vector<PassResource> resources(Access pair_access) const {
    const bool resampling = pair_access == Access::read;
    std::vector<PassResource> extra = {storage(BINDING_RESERVOIRS_IN, Access::read, state_.work),
                                       history_current(BINDING_PRIMARY, Access::read, state_.visibility),
                                       storage(BINDING_SPATIAL_PAIRS, pair_access, pair_shifts_)};
    if (resampling) {
      extra.push_back(storage(BINDING_SPATIAL_LIST, Access::read_write, list_));
      extra.push_back(storage(BINDING_SPATIAL_ARGS, Access::read_write, args_));
      extra.push_back(history_current(BINDING_DOMAINS, Access::read, state_.domain_ranges));  // DOMAIN_DISOCCLUDED (multilayer)
    }
    return restir_resources(state_, history_current(BINDING_RESERVOIRS_OUT, resampling ? Access::write : Access::read, state_.history),
                            std::move(extra));
  }

  const RestirState& state_;
  uint32_t pair_offsets_;
  bool pairs_;
  bool compact_;
  gpu::Buffer list_;
  gpu::Buffer args_;
  gpu::Buffer pair_shifts_;
  Pass pass_;
  std::unique_ptr<Pass> pairs_pass_;  // the pair shifts (pairs_ only)
};

}  // namespace

std::unique_ptr<Stage> make_spatial_stage(const RestirState& state) { return std::make_unique<SpatialStage>(state); }

}  // namespace strata::render
