#include "render/restir/restir_method.h"

#include <iterator>

#include "include/frame_data.h"
#include "render/restir/stages.h"
#include "restir/reservoir.h"
#include "restir/restir_data.h"

namespace strata::render {

RestirMethod::RestirMethod(const SharedResources& shared, const RenderSettings& settings, const MethodSpec& spec)
    : state_(shared, settings, spec) {
  const RestirOptions& o = settings.restir;
  const bool splat = spec.temporal == StageKind::temporal_splat;
  if (state_.primary_stage) primary_ = make_primary_stage(state_);
  if (state_.multilayer()) domain_init_ = make_domain_init_stage(state_);
  if (state_.splat_sort()) splat_sort_ = std::make_unique<SplatSortStage>(state_);
  initial_ = make_initial_stage(state_);
  if (o.temporal) temporal_ = splat ? make_temporal_splat_stage(state_, *splat_sort_) : make_temporal_gather_stage(state_);
  if (o.spatial) spatial_ = make_spatial_stage(state_);
  shade_ = make_shade_stage(state_);
  for (const Stage* s : {primary_.get(), domain_init_.get(), static_cast<Stage*>(splat_sort_.get()), initial_.get(), temporal_.get(),
                         spatial_.get(), shade_.get()})
    if (s) built_.push_back(s);
}

RestirMethod::~RestirMethod() = default;

uint32_t RestirMethod::timed_passes() const {
  uint32_t n = 0;
  for (const Stage* s : built_) n += s->timed_passes();
  return n;
}

// One ReSTIR frame, top to bottom (docs/ARCHITECTURE.md, "The frame"). Each stage names what it
// reads and writes; a stage that the method or the options leave out was not built and records
// nothing. The resources are RestirState's (ping-pong ones as this frame's current / previous).
void RestirMethod::record(VkCommandBuffer cmd, gpu::PassTimer& timer, const MethodFrame& f) {
  const StageFrame frame{cmd, timer, f, state_.shared.scene.parity()};
  last_parity_ = frame.parity;
  // primary: one camera ray per pixel -> visibility.current.
  if (primary_) primary_->record(frame);
  // domain_init (restir-multilayer): visibility.current, the previous frame's domains ->
  // domain_ranges, domain_list, domain_args (current).
  if (domain_init_) domain_init_->record(frame);
  // splat sort (splat methods): history.previous splatted forward -> splat lists, splat_offsets.
  // Before initial, which reads splat_offsets: pixels no splat reached take more candidates.
  if (splat_sort_) splat_sort_->record(frame);
  // initial: visibility.current, splat_offsets -> work (canonical samples), contribution.
  initial_->record(frame);
  // temporal (gather: history.previous at the backprojected pixel; splat: the sort's lists) and
  // work, visibility -> work.
  if (temporal_) temporal_->record(frame);
  // spatial: work, visibility.current -> history.current (the front layer: ML Sec. 5).
  if (spatial_) spatial_->record(frame);
  // commit: work -> history.current where spatial wrote nothing.
  record_commit(frame);
  // shade: contribution -> the image.
  shade_->record(frame);
}

// The frame's final reservoirs go to history.current: spatial writes them for the front layer;
// without spatial reuse every layer's temporal output (work) is copied, with it the deep layers'
// (restir-multilayer: spatial reuse is on the front layer only).
void RestirMethod::record_commit(const StageFrame& f) const {
  if (spatial_ && !state_.multilayer()) return;
  const VkDeviceSize front = spatial_ ? sizeof(gpu::PackedReservoir) * state_.pixels : 0;  // spatial wrote layer 0
  VkBufferCopy region{front, front, state_.work.size() - front};
  vkCmdCopyBuffer(f.cmd, state_.work.handle(), state_.history.current(f.parity).handle(), 1, &region);
  gpu::compute_barrier(f.cmd);
}

std::optional<DomainMap> RestirMethod::domain_map() const {
  if (!state_.multilayer()) return std::nullopt;
  return read_domain_map(state_.domain_ranges.current(last_parity_), state_.width, state_.height, state_.layers);
}

std::vector<PassDecision> RestirMethod::decisions() const {
  std::vector<PassDecision> d = {{"path_trace", false, std::string("method ") + state_.spec.name + " resamples instead"}};
  auto add = [&](const Stage* s, const char* pass, const std::string& absent) {
    d.push_back(s ? s->decision() : PassDecision{pass, false, absent});
  };
  add(primary_.get(), "primary", "no stage reads primary hits (restir.temporal = false, restir.spatial = false)");
  add(domain_init_.get(), "domain_init",
      state_.spec.layers ? "one layer (" + state_.layers_reason + "): single-layer domains, one per pixel"
                         : "single-layer domains: one per pixel");
  if (splat_sort_) d.push_back(splat_sort_->decision());
  add(initial_.get(), "initial", "");
  add(temporal_.get(), "temporal", "disabled (restir.temporal = false)");
  add(spatial_.get(), "spatial", "disabled (restir.spatial = false)");
  add(shade_.get(), "shade", "");
  return d;
}

std::map<std::string, uint64_t> RestirMethod::memory_bytes() const {
  auto m = state_.memory_bytes();
  for (const Stage* s : built_)
    for (const auto& [group, bytes] : s->memory_bytes()) m[group] += bytes;
  return m;
}

void RestirMethod::collect(std::span<const uint32_t> c, FrameStats& s) const {
  using namespace gpu;
  s.rays_traced.clear();  // the path tracer's kinds; ReSTIR counts by pass
  s.rays_traced["initial"] = c[COUNTER_RAYS_INITIAL];
  s.rays_traced["temporal"] = c[COUNTER_RAYS_TEMPORAL];
  s.rays_traced["spatial"] = c[COUNTER_RAYS_SPATIAL];
  static const char* reasons[SHIFT_REASONS] = {"ok", "primary", "replay", "structure", "occluded", "jacobian", "stale", "zero"};
  s.reuse["temporal.shifts"] = c[COUNTER_TEMPORAL_SHIFTS];
  s.reuse["temporal.no_history"] = c[COUNTER_TEMPORAL_NO_HISTORY];
  s.reuse["temporal.selected"] = c[COUNTER_TEMPORAL_SELECTED];
  s.reuse["temporal.validation_refused"] = c[COUNTER_TEMPORAL_INVALID];
  // Suffixes after x_k (restir/suffix_replay.glsl): traced again in the other frame, or kept.
  s.reuse["temporal.suffix_replayed"] = c[COUNTER_SUFFIX_REPLAYED];
  s.reuse["temporal.suffix_kept"] = c[COUNTER_SUFFIX_KEPT];
  s.reuse["temporal.replay_rays"] = uint64_t(c[COUNTER_RAYS_REPLAY]) + c[COUNTER_RAYS_REPLAY_RESAMPLE];
  for (const Stage* stage : built_) stage->collect(c, s);
  s.reuse["scene.instances_changed"] = state_.shared.scene.changed_instances();  // since the previous frame
  s.reuse["spatial.shifts"] = c[COUNTER_SPATIAL_SHIFTS];
  s.reuse["spatial.selected"] = c[COUNTER_SPATIAL_SELECTED];
  s.reuse["spatial.filtered"] = c[COUNTER_SPATIAL_FILTERED];  // candidates refused by the surface filter
  if (state_.shared.scene.has_lod_groups()) {
    // LoD-aware reuse (restir/lod_mapping.h): points resolved across a LoD switch, by outcome.
    // The COUNTER_LOD_* run in this order (shaders/include/frame_data.h); "refused": on another
    // level and not mapped (mapping off).
    static const char* lod[] = {"mappings", "unique", "matched", "failed_outside", "failed_ambiguous", "failed_degenerate", "uv_rays", "refused"};
    static_assert(COUNTER_LOD_REFUSED - COUNTER_LOD_MAPPINGS + 1 == std::size(lod));
    for (uint32_t i = 0; i < std::size(lod); ++i) s.reuse[std::string("lod.") + lod[i]] = c[COUNTER_LOD_MAPPINGS + i];
  }
  for (uint32_t r = 1; r < SHIFT_REASONS; ++r) {
    s.shift_failures[std::string("temporal.") + reasons[r]] = c[COUNTER_TEMPORAL_FAIL + r];
    s.shift_failures[std::string("spatial.") + reasons[r]] = c[COUNTER_SPATIAL_FAIL + r];
  }
}

}  // namespace strata::render
