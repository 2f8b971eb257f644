#include "render/renderer.h"

#include <algorithm>

#include "render/frame_constants.h"
#include "render/light_sampler_choice.h"
#include "render/method_table.h"
#include "restir/layer_data.h"
#include "restir/restir_limits.h"

namespace strata::render {
namespace {

void require(bool ok, const std::string& message) {
  if (!ok) throw std::invalid_argument(message);
}

}  // namespace

void RenderSettings::validate() const {
  auto in = [](uint64_t v, uint64_t lo, uint64_t hi) { return v >= lo && v <= hi; };
  require(in(width, 1, RenderLimits::max_dimension),
          "width = " + std::to_string(width) + " is outside [1, " + std::to_string(RenderLimits::max_dimension) + "]");
  require(in(height, 1, RenderLimits::max_dimension),
          "height = " + std::to_string(height) + " is outside [1, " + std::to_string(RenderLimits::max_dimension) + "]");
  require(uint64_t(width) * height <= RenderLimits::max_pixels,
          "width * height = " + std::to_string(uint64_t(width) * height) + " exceeds max_pixels = " +
              std::to_string(RenderLimits::max_pixels));
  require(in(spp, 1, RenderLimits::max_spp), "spp = " + std::to_string(spp) + " is outside [1, " + std::to_string(RenderLimits::max_spp) + "]");
  require(in(max_depth, 1, RenderLimits::max_depth),
          "max_depth = " + std::to_string(max_depth) + " is outside [1, " + std::to_string(RenderLimits::max_depth) + "]");
  require(in(samples_per_dispatch, 1, 4096), "samples_per_dispatch = " + std::to_string(samples_per_dispatch) + " is outside [1, 4096]");
  const MethodSpec& spec = method_spec(method);
  if (spec.reuse) {
    require(spp == 1, "spp = " + std::to_string(spp) + " but method " + method +
                          " keeps one reservoir per pixel and shades one sample per frame; use restir.initial_candidates "
                          "for more candidates per frame (spp must be 1)");
    restir.validate();
  }
}

std::optional<DomainMap> Renderer::domain_map() const { return method_->domain_map(); }

Renderer::Renderer(const gpu::Context& ctx, const scene::Scene& scene, RenderSettings settings)
    : ctx_(ctx), settings_(std::move(settings)) {
  settings_.validate();
  // Temporal reuse needs the previous frame's TLAS and instances on the device; `pt` keeps none.
  scene_ = std::make_unique<GpuScene>(ctx, scene, /*keep_history=*/method_spec(settings_.method).reuse,
                                      /*light_tree=*/light_sampler_in_use(settings_.restir.light_sampler, bounded_lights(scene)) ==
                                          LightSampler::tree);
  const RestirOptions& ro = settings_.restir;
  scene_->set_lod_mapping({.uv = ro.lod_mapping != LodMapping::off,
                           .matching = ro.lod_matching,
                           .vertices = static_cast<uint32_t>(ro.lod_vertices)});
  size_t pixels = size_t(settings_.width) * settings_.height;
  constants_ = gpu::Buffer(ctx, sizeof(gpu::GpuFrameConstants), VK_BUFFER_USAGE_UNIFORM_BUFFER_BIT, gpu::Memory::Host, "frame constants");
  counters_ = gpu::Buffer(ctx, sizeof(uint32_t) * gpu::COUNTER_COUNT, gpu::k_storage_usage, gpu::Memory::Device, "counters");
  accum_ = gpu::Buffer(ctx, sizeof(glm::vec4) * pixels, gpu::k_storage_usage, gpu::Memory::Device, "accumulation");
  method_ = make_method(settings_, SharedResources{ctx, *scene_, constants_, counters_, accum_});
  // "deform" (scenes with deforming instances), "update", then the method's
  timer_ = std::make_unique<gpu::PassTimer>(ctx, (scene_->deformation() ? 2 : 1) + method_->timed_passes());
}

Renderer::~Renderer() = default;

std::map<std::string, uint64_t> Renderer::memory_bytes() const {
  SceneMemory mem = scene_->memory();
  std::map<std::string, uint64_t> m = {{"geometry", mem.geometry},
                                       {"acceleration", mem.acceleration},
                                       {"scene_per_frame", mem.per_frame},
                                       {"image", accum_.size()},
                                       {"frame_constants_and_counters", constants_.size() + counters_.size()}};
  if (mem.history > 0) m["scene_history"] = mem.history;
  if (mem.lod_uv > 0) m["lod_uv_space"] = mem.lod_uv;
  if (mem.textures > 0) m["textures"] = mem.textures;
  if (mem.environment > 0) m["environment"] = mem.environment;
  if (mem.deformation > 0) m["deformation"] = mem.deformation;
  for (const auto& [group, bytes] : method_->memory_bytes()) m[group] += bytes;
  return m;
}

FrameResult Renderer::render(const scene::FrameState& frame, uint32_t frame_index, bool accumulate) {
  const auto& sc = scene_->scene();
  if (frame.transforms.size() != sc.instances.size() || frame.lods.size() != sc.instances.size())
    throw std::invalid_argument("frame state has " + std::to_string(frame.transforms.size()) + " transforms and " +
                                std::to_string(frame.lods.size()) + " LoD levels for " + std::to_string(sc.instances.size()) + " instances");
  for (size_t i = 0; i < frame.lods.size(); ++i)
    if (frame.lods[i] >= sc.instances[i].lod_meshes.size())
      throw std::invalid_argument("lods[" + std::to_string(i) + "] = " + std::to_string(frame.lods[i]) + " but instance has " +
                                  std::to_string(sc.instances[i].lod_meshes.size()) + " levels");
  if (frame.lights.size() != sc.lights.size())
    throw std::invalid_argument("frame state has " + std::to_string(frame.lights.size()) + " light transforms for " +
                                std::to_string(sc.lights.size()) + " lights");
  const bool env_nee = environment_nee(sc.environment, scene_->has_emitters() || scene_->has_punctual());
  if (!accumulate) accumulated_spp_ = 0;
  uint32_t tlas_builds_before = scene_->tlas_builds(), tlas_refits_before = scene_->tlas_refits();
  const SceneDeformation* deformation = scene_->deformation();
  const uint32_t blas_refits_before = deformation ? deformation->refits() : 0;
  const uint32_t blas_rebuilds_before = deformation ? deformation->rebuilds() : 0;

  ctx_.submit_and_wait([&](VkCommandBuffer cmd) {
    timer_->reset(cmd);
    if (scene_->deformation()) {
      timer_->begin(cmd, "deform");
      scene_->record_deformation(cmd, frame);
      timer_->end(cmd);
    }
    timer_->begin(cmd, "update");
    scene_->record_update(cmd, frame);
    if (!accumulate) vkCmdFillBuffer(cmd, accum_.handle(), 0, VK_WHOLE_SIZE, 0);
    vkCmdFillBuffer(cmd, counters_.handle(), 0, VK_WHOLE_SIZE, 0);
    gpu::compute_barrier(cmd);
    timer_->end(cmd);

    FrameSetup setup{settings_.width, settings_.height, frame_index,       settings_.seed,
                     settings_.spp,   settings_.max_depth, env_nee, settings_.restir.splats_per_frame,
                     method_->fixed_primary(), history_held_};
    gpu::GpuFrameConstants c = make_frame_constants(frame, sc.environment, *scene_, setup);
    constants_.upload(&c, sizeof c);

    method_->record(cmd, *timer_,
                    MethodFrame{frame, frame_index, accumulated_spp_, env_nee, scene_->history_valid() && !history_held_, history_held_,
                                scene_->moved_since_previous()});
  });
  accumulated_spp_ += settings_.spp;

  FrameResult r;
  r.accumulated_spp = accumulated_spp_;
  auto accum = accum_.download_as<glm::vec4>(size_t(settings_.width) * settings_.height);
  r.image.width = settings_.width;
  r.image.height = settings_.height;
  r.image.rgba.resize(accum.size() * 4);
  for (size_t i = 0; i < accum.size(); ++i) {
    float n = accum[i].a > 0.0f ? accum[i].a : 1.0f;
    r.image.rgba[4 * i + 0] = accum[i].r / n;
    r.image.rgba[4 * i + 1] = accum[i].g / n;
    r.image.rgba[4 * i + 2] = accum[i].b / n;
    r.image.rgba[4 * i + 3] = 1.0f;
  }
  auto counters = counters_.download_as<uint32_t>(gpu::COUNTER_COUNT);
  FrameStats& s = r.stats;
  s.frame = frame_index;
  s.pixels = uint64_t(settings_.width) * settings_.height;
  s.pass_ms = timer_->read();
  for (const auto& p : s.pass_ms) s.gpu_ms_total += p.ms;
  s.rays_traced = {{"primary", counters[gpu::COUNTER_RAYS_PRIMARY]},
                   {"bounce", counters[gpu::COUNTER_RAYS_BOUNCE]},
                   {"shadow", counters[gpu::COUNTER_RAYS_SHADOW]}};
  s.paths = counters[gpu::COUNTER_PATHS];
  s.nonfinite_rejected = counters[gpu::COUNTER_NONFINITE_REJECTED];
  method_->collect(counters, s);
  s.memory_bytes = memory_bytes();
  s.tlas_builds = scene_->tlas_builds() - tlas_builds_before;
  s.tlas_refits = scene_->tlas_refits() - tlas_refits_before;
  s.passes.clear();
  if (const SceneDeformation* d = scene_->deformation()) {
    const uint32_t refits = d->refits() - blas_refits_before, rebuilds = d->rebuilds() - blas_rebuilds_before;
    s.passes.push_back({"deform", true,
                        std::to_string(d->deformed_vertices()) + " vertices of the skinned and morphing instances; their BLAS " +
                            std::to_string(refits) + " refit, " + std::to_string(rebuilds) +
                            " rebuilt (a rebuild when a box's surface area grew past " +
                            std::to_string(SceneDeformation::k_rebuild_growth).substr(0, 3) + "x that of its last build)"});
  }
  s.passes.push_back({"update", true, s.tlas_refits ? "TLAS refit (transforms only)" : "TLAS build"});
  for (auto& d : method_->decisions()) s.passes.push_back(std::move(d));
  return r;
}

}  // namespace strata::render
