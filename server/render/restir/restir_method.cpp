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
  for (StageKind kind : spec.stages()) {
    switch (kind) {
      case StageKind::initial: stages_.push_back(make_initial_stage(state_)); break;
      case StageKind::temporal_gather:
        if (o.temporal) stages_.push_back(make_temporal_gather_stage(state_));
        break;
      case StageKind::temporal_splat:
        if (o.temporal) stages_.push_back(make_temporal_splat_stage(state_));
        break;
      case StageKind::spatial:
        if (o.spatial) stages_.push_back(make_spatial_stage(state_));
        break;
      case StageKind::shade: stages_.push_back(make_shade_stage(state_)); break;
      case StageKind::primary:
        if (state_.primary_stage) stages_.push_back(make_primary_stage(state_));
        break;
      case StageKind::domain_init:
        if (state_.multilayer()) stages_.push_back(make_domain_init_stage(state_));
        break;
      case StageKind::path_trace: break;
    }
  }
}

RestirMethod::~RestirMethod() = default;

uint32_t RestirMethod::timed_passes() const {
  uint32_t n = 0;
  for (const auto& s : stages_) n += s->timed_passes();
  return n;
}

const Stage* RestirMethod::find(StageKind kind) const {
  for (const auto& s : stages_)
    if (s->kind() == kind) return s.get();
  return nullptr;
}

// The frame: primary -> [domain_init] -> [splat sort] -> initial -> temporal -> spatial -> shade
// (the splat stage's counting sort runs before the initial stage: Stage::record_before_initial). The stage that writes the
// frame's final reservoirs into history.current is spatial; without it, the temporal output (work) is
// copied there. Spatial reuse is on the front layer only (ML Sec. 5), so the deep layers' temporal
// output is copied in either case.
void RestirMethod::record(VkCommandBuffer cmd, gpu::PassTimer& timer, const MethodFrame& f) {
  const StageFrame frame{cmd, timer, f, state_.shared.scene.parity()};
  last_parity_ = frame.parity;
  const bool spatial = find(StageKind::spatial) != nullptr;
  for (const auto& stage : stages_) {
    if (stage->kind() == StageKind::initial)
      for (const auto& early : stages_) early->record_before_initial(frame);
    if (stage->kind() == StageKind::shade && (!spatial || state_.multilayer())) {
      const VkDeviceSize front = spatial ? sizeof(gpu::PackedReservoir) * state_.pixels : 0;  // spatial wrote layer 0
      VkBufferCopy region{front, front, state_.work.size() - front};
      vkCmdCopyBuffer(cmd, state_.work.handle(), state_.history.current(frame.parity).handle(), 1, &region);
      gpu::compute_barrier(cmd);
    }
    stage->record(frame);
  }
}

std::optional<DomainMap> RestirMethod::domain_map() const {
  if (!state_.multilayer()) return std::nullopt;
  return read_domain_map(state_.domain_ranges.current(last_parity_), state_.width, state_.height, state_.layers);
}

std::vector<PassDecision> RestirMethod::decisions() const {
  std::vector<PassDecision> d = {{"path_trace", false, std::string("method ") + state_.spec.name + " resamples instead"}};
  auto add = [&](StageKind kind, const char* pass, const std::string& absent) {
    if (const Stage* s = find(kind)) d.push_back(s->decision());
    else d.push_back({pass, false, absent});
  };
  add(StageKind::primary, "primary", "no stage reads primary hits (restir.temporal = false, restir.spatial = false)");
  add(StageKind::domain_init, "domain_init",
      state_.spec.layers ? "one layer (" + state_.layers_reason + "): single-layer domains, one per pixel"
                         : "single-layer domains: one per pixel");
  add(StageKind::initial, "initial", "");
  add(state_.spec.temporal, "temporal", "disabled (restir.temporal = false)");
  add(StageKind::spatial, "spatial", "disabled (restir.spatial = false)");
  add(StageKind::shade, "shade", "");
  return d;
}

std::map<std::string, uint64_t> RestirMethod::memory_bytes() const {
  auto m = state_.memory_bytes();
  for (const auto& s : stages_)
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
  for (const auto& stage : stages_) stage->collect(c, s);
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
