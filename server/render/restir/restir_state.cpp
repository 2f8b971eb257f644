#include "render/restir/restir_state.h"

#include <algorithm>

#include "include/bindings.h"
#include "gpu/pipeline_warmup.h"
#include "render/restir/layer_count.h"
#include "include/scene_data.h"
#include "restir/layer_data.h"
#include "restir/primary_data.h"
#include "restir/reservoir.h"
#include "restir/restir_data.h"

namespace strata::render {
namespace {

// ML Sec. 5: "we define the depth range as [(1-e)t, (1+e)t] and use e = 0.01".
constexpr float k_depth_range_epsilon = 0.01f;

gpu::GpuRestirConstants make_constants(const RenderSettings& s, const MethodSpec& spec, uint32_t layers, bool splat_sort) {
  const RestirOptions& o = s.restir;
  gpu::GpuRestirConstants c{};
  c.initial_candidates = o.initial_candidates;
  c.light_candidates = o.light_candidates;
  c.shift_mode = static_cast<uint32_t>(o.shift);
  c.mis_mode = static_cast<uint32_t>(o.mis);
  // The still test reads the domain's primary vertex (gather) or pixel-centre hit (splat).
  c.confidence_cap = o.moving_cap(spec);
  c.still_confidence_cap = o.still_cap(spec);
  c.spatial_radius = o.spatial_radius_pixels(s.height);
  c.spatial_neighbors = o.spatial_neighbors;
  c.disocclusion_spatial_neighbors = o.disocclusion_spatial_neighbors;
  c.flags = (o.unbiased ? gpu::RESTIR_UNBIASED : 0u) | (spec.backup ? gpu::RESTIR_SPLAT_BACKUP : 0u) |
            (o.temporal_filter ? gpu::RESTIR_TEMPORAL_FILTER : 0u);
  c.splats_per_frame = o.splats_per_frame;
  c.direct_strata = o.direct_strata_used(spec);
  c.albedo_strata = o.albedo_strata_used(spec);
  c.colour_cv = o.colour_cv_used(spec);
  c.colour_cv_spread = o.colour_cv_spread;
  c.suffix_mode = static_cast<uint32_t>(o.suffix);
  // ReSTIR DI: camera, x1, light (one bounce).
  c.max_segments = spec.direct_lighting || o.direct_lighting ? std::min<uint32_t>(2, s.max_depth) : s.max_depth;
  c.layers = layers;
  c.hole_fill_radius = o.hole_fill_radius;
  c.layer_mode = static_cast<uint32_t>(o.layer_mode);
  c.depth_range_epsilon = k_depth_range_epsilon;
  c.view_layer = o.view_layer;
  // Only where the splat counting sort runs before the initial stage (it says where no splat landed).
  c.disocclusion_initial_candidates = splat_sort ? o.disocclusion_candidates(spec, layers) : 0u;
  return c;
}

}  // namespace

std::string no_history_reason(bool held) {
  if (held) return "held: its pipelines are compiling in the background, so each frame's reuse starts afresh until they are done";
  return "no previous frame yet";
}

std::string suffix_decision(Suffix suffix_option, bool scene_moved, uint32_t changed_instances) {
  if (!scene_moved) return "suffixes kept (nothing moved)";
  if (suffix_option == Suffix::fail) return "suffixes refused (suffix fail: the scene changed)";
  if (suffix_option == Suffix::cached) return "suffixes cached (suffix cached: stored radiance, biased)";
  if (suffix_option == Suffix::replay) return "suffixes replayed (the scene changed)";
  const std::string changed = std::to_string(changed_instances) + " changed instance" + (changed_instances == 1 ? "" : "s");
  if (changed_instances > gpu::SWEPT_BOXES_MAX)
    return "suffixes replayed (suffix auto: " + changed + ", more than the " + std::to_string(gpu::SWEPT_BOXES_MAX) +
           " swept boxes the per-path test lists)";
  return "suffixes of one segment whose ray misses the swept boxes of the " + changed +
         " kept (suffix auto: the same light in both frames), the others replayed";
}

RestirState::RestirState(const SharedResources& shared_resources, const RenderSettings& render_settings, const MethodSpec& method)
    : shared(shared_resources),
      settings(render_settings),
      spec(method),
      width(render_settings.width),
      height(render_settings.height),
      layers(1),
      primary_stage(render_settings.restir.visibility_buffer(method.fixed_primary)) {
  const auto& ctx = shared.ctx;
  if (spec.layers) {
    if (settings.restir.layers > 0) {
      layers = settings.restir.layers;
      layers_reason = "requested";
    } else if (gpu::recording_pipelines()) {
      // Only the pipelines are being recorded (a session's start asks whether they are compiled),
      // so nothing can be measured on the device: every count above 1 creates the same pipelines.
      layers = 2;
      layers_reason = "recording pipelines";
    } else {
      const auto& scene = shared.scene.scene();
      LayerCount measured = measure_layers(shared.ctx, scene, scene.frame_state(0), width, height);
      layers = measured.layers;
      layers_reason = measured.reason;
    }
  }
  if (settings.restir.view_layer >= layers)
    throw std::runtime_error("restir.view_layer = " + std::to_string(settings.restir.view_layer) + " is outside [0, " +
                             std::to_string(layers - 1) + "]: the method has " + std::to_string(layers) + " layer" +
                             (layers == 1 ? "" : "s") + (spec.layers ? " (" + layers_reason + ")" : ""));
  pixels = uint64_t(width) * height;
  domains = pixels * layers;
  constants = gpu::Buffer(ctx, sizeof(gpu::GpuRestirConstants), VK_BUFFER_USAGE_UNIFORM_BUFFER_BIT, gpu::Memory::Host, "restir constants");
  gpu::GpuRestirConstants c = make_constants(settings, spec, layers, splat_sort());
  c.silhouette_band = silhouette_band();
  c.reveal_lookahead = reveal_lookahead();
  if (deep_backup()) c.flags |= gpu::RESTIR_DEEP_BACKUP;
  constants.upload(&c, sizeof c);
  work = device_storage(ctx, sizeof(gpu::PackedReservoir) * domains, "reservoirs (work)");
  history = PingPong(ctx, sizeof(gpu::PackedReservoir) * domains, "reservoirs (history)");
  // Per domain f(Y) of the reservoir there, per pixel what the camera rays see directly, per
  // domain the estimate the shade pass adds (restir/domain.h).
  // With the colour control variate, per pixel the initial estimate and the reused window pixels.
  const uint64_t colour_cv_sections = c.colour_cv > 0.0f ? 1 : 0;
  contribution = device_storage(ctx, sizeof(glm::vec4) * (2 * domains + (4 + colour_cv_sections) * pixels), "contribution");
  // The temporal stages, the spatial stage's neighbour filter and, with fixed primary vertices, the
  // initial stage read the visibility buffer. Without any of them there is no primary stage, and
  // the initial pass binds one entry that it never reads (its layout has the binding).
  const size_t entries = primary_stage ? size_t(domains) : 1;
  visibility = PingPong(ctx, sizeof(gpu::GpuPrimaryHit) * entries, "visibility buffer");
  primary_material = PingPong(ctx, sizeof(gpu::GpuPrimaryMaterial) * (primary_material_kept() ? size_t(pixels) : 1),
                              "primary materials");
  const size_t offset_entries = splat_sort() ? size_t(domains) + 1 : 1;
  splat_offsets = device_storage(ctx, sizeof(uint32_t) * offset_entries, "splat offsets");
  const size_t layer_entries = multilayer() ? size_t(domains) : 1;
  domain_ranges = PingPong(ctx, sizeof(gpu::GpuDomainRange) * layer_entries, "domain ranges");
  domain_marks = device_storage(ctx, sizeof(gpu::GpuDomainMark) * layer_entries, "domain marks");
  // The list holds deep domains only: (k - 1) x pixels at most.
  const size_t list_entries = multilayer() ? size_t(domains - pixels) : 1;
  domain_list = PingPong(ctx, sizeof(uint32_t) * list_entries, "domain list");
  // DOMAIN_ARGS_ACTIVE, then DOMAIN_ARGS_DORMANT (restir/layer_data.h).
  domain_args = PingPong(ctx, 2 * sizeof(gpu::GpuDomainArgs), "domain list arguments", gpu::k_indirect_usage);
}

std::map<std::string, uint64_t> RestirState::memory_bytes() const {
  std::map<std::string, uint64_t> m = {{"reservoirs", work.size() + history.size()},
                                       {"contribution", contribution.size()},
                                       {"frame_constants_and_counters", constants.size()}};
  if (primary_stage) m["visibility"] = visibility.size();
  if (primary_material_kept()) m["primary_material"] = primary_material.size();
  if (multilayer()) m["domains"] = domain_ranges.size() + domain_marks.size() + domain_list.size() + domain_args.size();
  return m;
}

std::vector<PassResource> restir_resources(const RestirState& state, PassResource out, std::vector<PassResource> extra) {
  std::vector<PassResource> r = {uniform(BINDING_FRAME, state.shared.constants), uniform(BINDING_RESTIR, state.constants),
                                 storage(BINDING_COUNTERS, Access::read_write, state.shared.counters), std::move(out),
                                 storage(BINDING_CONTRIBUTION, Access::read_write, state.contribution),
                                 history_current(BINDING_PRIMARY_MATERIAL, Access::read, state.primary_material),
                                 history_previous(BINDING_PRIMARY_MATERIAL_PREV, state.primary_material)};
  for (auto& e : extra) r.push_back(std::move(e));
  return r;
}

}  // namespace strata::render
