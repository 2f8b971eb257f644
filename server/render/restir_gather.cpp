#include "render/restir_gather.h"

#include "include/bindings.h"
#include "include/frame_data.h"
#include "restir/reservoir.h"
#include "restir/restir_data.h"

namespace strata::render {
namespace {

constexpr VkDescriptorType k_storage = VK_DESCRIPTOR_TYPE_STORAGE_BUFFER;
constexpr VkDescriptorType k_uniform = VK_DESCRIPTOR_TYPE_UNIFORM_BUFFER;

gpu::GpuRestirConstants make_constants(const RenderSettings& s) {
  const RestirOptions& o = s.restir;
  gpu::GpuRestirConstants c{};
  c.initial_candidates = o.initial_candidates;
  c.light_candidates = o.light_candidates;
  c.shift_mode = o.shift == "reconnection" ? gpu::SHIFT_RECONNECTION : gpu::SHIFT_HYBRID;
  c.mis_mode = o.mis == "balance" ? gpu::MIS_BALANCE : gpu::MIS_PAIRWISE;
  c.confidence_cap = o.confidence_cap;
  c.spatial_radius = o.spatial_radius;
  c.spatial_neighbors = o.spatial_neighbors;
  c.flags = (o.unbiased ? gpu::RESTIR_UNBIASED : 0u) | (s.method == "restir-splat-backup" ? gpu::RESTIR_SPLAT_BACKUP : 0u);
  // ReSTIR DI: camera, x1, light (one bounce).
  c.splats_per_frame = o.splats_per_frame;
  c.max_segments = o.direct_lighting ? std::min<uint32_t>(2, s.max_depth) : s.max_depth;
  return c;
}

}  // namespace

// One pass: its pipeline and a descriptor set per frame parity (the scene's history slots and the
// ping-pong reservoir buffers swap roles every frame).
struct RestirGather::Pass {
  gpu::ComputePipeline pipeline;
  std::array<std::unique_ptr<gpu::DescriptorSet>, 2> sets;
  Pass(const gpu::Context& ctx, const char* shader, std::vector<gpu::Binding> bindings)
      : pipeline(ctx, shader, bindings, std::vector<gpu::SpecConstant>{}, 0) {
    for (auto& s : sets) s = std::make_unique<gpu::DescriptorSet>(ctx, pipeline);
  }
};

RestirGather::RestirGather(const SharedResources& shared, const RenderSettings& settings)
    : shared_(shared), settings_(settings) {
  const auto& ctx = shared.ctx;
  size_t pixels = size_t(settings.width) * settings.height;
  restir_constants_ = gpu::Buffer(ctx, sizeof(gpu::GpuRestirConstants), VK_BUFFER_USAGE_UNIFORM_BUFFER_BIT, gpu::Memory::Host,
                                  "restir constants");
  gpu::GpuRestirConstants c = make_constants(settings);
  restir_constants_.upload(&c, sizeof c);
  work_ = gpu::Buffer(ctx, sizeof(gpu::PackedReservoir) * pixels, gpu::k_storage_usage, gpu::Memory::Device, "reservoirs (work)");
  for (auto& h : history_)
    h = gpu::Buffer(ctx, sizeof(gpu::PackedReservoir) * pixels, gpu::k_storage_usage, gpu::Memory::Device, "reservoirs (history)");
  // Per pixel: f(Y) of the reservoir there, then (second half) what the camera rays see directly.
  contribution_ = gpu::Buffer(ctx, 2 * sizeof(glm::vec4) * pixels, gpu::k_storage_usage, gpu::Memory::Device, "contribution");

  auto common = [](bool lights, bool history) {
    auto b = GpuScene::bindings(lights, history);
    b.push_back({BINDING_FRAME, k_uniform});
    b.push_back({BINDING_RESTIR, k_uniform});
    b.push_back({BINDING_COUNTERS, k_storage});
    b.push_back({BINDING_RESERVOIRS_OUT, k_storage});
    b.push_back({BINDING_CONTRIBUTION, k_storage});
    return b;
  };
  auto with_in = [](std::vector<gpu::Binding> b) {
    b.push_back({BINDING_RESERVOIRS_IN, k_storage});
    return b;
  };
  initial_ = std::make_unique<Pass>(ctx, "restir_initial", common(true, false));
  const bool splat = settings.method == "restir-splat" || settings.method == "restir-splat-backup";
  if (settings.restir.temporal && !splat) temporal_ = std::make_unique<Pass>(ctx, "restir_temporal", with_in(common(false, true)));
  if (settings.restir.temporal && splat)
    splat_ = std::make_unique<SplatTemporal>(shared, settings.width, settings.height, restir_constants_, work_, history_, contribution_);
  if (settings.restir.spatial) spatial_ = std::make_unique<Pass>(ctx, "restir_spatial", with_in(common(false, false)));
  shade_ = std::make_unique<Pass>(ctx, "restir_shade",
                                  std::vector<gpu::Binding>{{BINDING_FRAME, k_uniform},
                                                            {BINDING_COUNTERS, k_storage},
                                                            {BINDING_RESERVOIRS_IN, k_storage},
                                                            {BINDING_CONTRIBUTION, k_storage},
                                                            {BINDING_ACCUM, k_storage}});

  for (int parity = 0; parity < 2; ++parity) {
    const gpu::Buffer& current = history_[size_t(parity)];
    const gpu::Buffer& previous = history_[size_t(1 - parity)];
    auto bind_common = [&](Pass& p, bool lights, bool history) {
      auto& set = *p.sets[size_t(parity)];
      shared.scene.bind(set, lights, history, parity);
      set.bind_buffer(BINDING_FRAME, shared.constants);
      set.bind_buffer(BINDING_RESTIR, restir_constants_);
      set.bind_buffer(BINDING_COUNTERS, shared.counters);
      set.bind_buffer(BINDING_CONTRIBUTION, contribution_);
      return &set;
    };
    bind_common(*initial_, true, false)->bind_buffer(BINDING_RESERVOIRS_OUT, work_);
    if (temporal_) {
      auto* set = bind_common(*temporal_, false, true);
      set->bind_buffer(BINDING_RESERVOIRS_IN, previous);
      set->bind_buffer(BINDING_RESERVOIRS_OUT, work_);
    }
    if (spatial_) {
      auto* set = bind_common(*spatial_, false, false);
      set->bind_buffer(BINDING_RESERVOIRS_IN, work_);
      set->bind_buffer(BINDING_RESERVOIRS_OUT, current);
    }
    auto& shade = *shade_->sets[size_t(parity)];
    shade.bind_buffer(BINDING_FRAME, shared.constants);
    shade.bind_buffer(BINDING_COUNTERS, shared.counters);
    shade.bind_buffer(BINDING_RESERVOIRS_IN, current);
    shade.bind_buffer(BINDING_CONTRIBUTION, contribution_);
    shade.bind_buffer(BINDING_ACCUM, shared.accum);
  }
}

RestirGather::~RestirGather() = default;

void RestirGather::record(VkCommandBuffer cmd, gpu::PassTimer& timer, const MethodFrame& f) {
  const size_t parity = size_t(shared_.scene.parity());
  const uint32_t w = settings_.width, h = settings_.height;
  timer.begin(cmd, "initial");
  gpu::dispatch_2d(cmd, initial_->pipeline, *initial_->sets[parity], w, h);
  gpu::compute_barrier(cmd);
  timer.end(cmd);

  ran_temporal_ = (temporal_ || splat_) && f.history_valid;
  temporal_reason_ = !(temporal_ || splat_) ? "disabled (restir.temporal = false)" : !f.history_valid ? "no previous frame yet" : "";
  if (ran_temporal_ && splat_) {
    partitions_ = f.frame.camera_open ? settings_.restir.splats_per_frame : 1u;  // K (RS-main Eq. 19)
    splat_->record(cmd, timer, int(parity), partitions_);
  } else if (ran_temporal_) {
    timer.begin(cmd, "temporal");
    gpu::dispatch_2d(cmd, temporal_->pipeline, *temporal_->sets[parity], w, h);
    gpu::compute_barrier(cmd);
    timer.end(cmd);
  }
  if (spatial_) {
    timer.begin(cmd, "spatial");
    gpu::dispatch_2d(cmd, spatial_->pipeline, *spatial_->sets[parity], w, h);
    gpu::compute_barrier(cmd);
    timer.end(cmd);
  } else {
    // Without spatial reuse the temporal output is the frame's final reservoir.
    VkBufferCopy region{0, 0, work_.size()};
    vkCmdCopyBuffer(cmd, work_.handle(), history_[parity].handle(), 1, &region);
    gpu::compute_barrier(cmd);
  }
  timer.begin(cmd, "shade");
  gpu::dispatch_2d(cmd, shade_->pipeline, *shade_->sets[parity], w, h);
  gpu::compute_barrier(cmd);
  timer.end(cmd);
}

std::vector<PassDecision> RestirGather::decisions() const {
  const RestirOptions& o = settings_.restir;
  std::string paths = o.direct_lighting ? "one-bounce paths (ReSTIR DI)" : "paths of up to " + std::to_string(settings_.max_depth) + " segments";
  return {{"path_trace", false, "method " + settings_.method + " resamples instead"},
          {"primary", false, "gather backprojects the pixel-centre hit inside temporal"},
          {"domain_init", false, "single-layer domains: one per pixel"},
          {"initial", true, std::to_string(o.initial_candidates) + " candidate path(s), " + std::to_string(o.light_candidates) +
                                " light candidate(s) per vertex, " + paths},
          {"temporal", ran_temporal_,
           !ran_temporal_ ? temporal_reason_
           : splat_       ? std::string(settings_.method == "restir-splat-backup" ? "splat with backup sample" : "splat") +
                                " (counting sort; reprojection + " + o.shift + " shift, reverse-splat MIS, bilinear confidence" +
                                (partitions_ > 1 ? "; " + std::to_string(partitions_) + " time partitions over the shutter)" : ")")
                          : "gather, " + o.shift + " shift, " + (o.unbiased ? "reverse-shift MIS" : "confidence weights (biased)")},
          {"spatial", bool(spatial_), spatial_ ? std::to_string(o.spatial_neighbors) + " neighbour(s), " + o.mis + " MIS"
                                               : "disabled (restir.spatial = false)"},
          {"shade", true, "f(Y) W"}};
}

std::map<std::string, uint64_t> RestirGather::memory_bytes() const {
  std::map<std::string, uint64_t> m = {{"reservoirs", work_.size() + history_[0].size() + history_[1].size()},
                                       {"contribution", contribution_.size()},
                                       {"frame_constants_and_counters", restir_constants_.size()}};
  if (splat_)
    for (const auto& [group, bytes] : splat_->memory_bytes()) m[group] += bytes;
  return m;
}

void RestirGather::collect(std::span<const uint32_t> c, FrameStats& s) const {
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
  if (splat_) {
    // RS-main statistics of splatting: splats per pixel (mean over pixels is landed / pixels), the
    // fullest pixel, and holes (pixels no splat reached: temporal.no_history).
    s.reuse["splat.landed"] = c[COUNTER_SPLATS_LANDED];
    s.reuse["splat.max_per_pixel"] = c[COUNTER_SPLATS_MAX];
    s.reuse["splat.partitions"] = ran_temporal_ ? partitions_ : 0;  // K time partitions of this frame's shutter
    s.reuse["splat.holes"] = c[COUNTER_TEMPORAL_NO_HISTORY];
    s.reuse["splat.visibility_failed"] = c[COUNTER_TEMPORAL_FAIL + SHIFT_FAIL_PRIMARY];
    if (settings_.method == "restir-splat-backup") s.reuse["splat.backup_selected"] = c[COUNTER_SPLAT_BACKUP_SELECTED];
  }
  s.reuse["spatial.shifts"] = c[COUNTER_SPATIAL_SHIFTS];
  s.reuse["spatial.selected"] = c[COUNTER_SPATIAL_SELECTED];
  for (uint32_t r = 1; r < SHIFT_REASONS; ++r) {
    s.shift_failures[std::string("temporal.") + reasons[r]] = c[COUNTER_TEMPORAL_FAIL + r];
    s.shift_failures[std::string("spatial.") + reasons[r]] = c[COUNTER_SPATIAL_FAIL + r];
  }
}

}  // namespace strata::render
