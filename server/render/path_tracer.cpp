#include "render/path_tracer.h"

#include <algorithm>

#include "include/bindings.h"
#include "include/frame_data.h"

namespace strata::render {
namespace {

std::vector<gpu::Binding> path_trace_bindings(const GpuScene& scene) {
  auto b = scene.bindings(/*with_lights=*/true);
  b.push_back({BINDING_FRAME, VK_DESCRIPTOR_TYPE_UNIFORM_BUFFER});
  b.push_back({BINDING_COUNTERS, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER});
  b.push_back({BINDING_ACCUM, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER});
  return b;
}

// The parts of the path tracer a frame needs, as specialization constants.
struct Features {
  bool thin_lens, env_nee, emitters, motion_blur, punctual;
  uint32_t key() const {
    return uint32_t(thin_lens) | uint32_t(env_nee) << 1 | uint32_t(emitters) << 2 | uint32_t(motion_blur) << 3 |
           uint32_t(punctual) << 4;
  }
};

// A scene without punctual lights leaves SPEC_PUNCTUAL out, one without alpha SPEC_ALPHA_TEST: the
// pipeline is the one it always was.
std::vector<gpu::SpecConstant> spec(const GpuScene& scene, Features f) {
  std::vector<gpu::SpecConstant> s{{SPEC_THIN_LENS, f.thin_lens}, {SPEC_ENV_NEE, f.env_nee}, {SPEC_EMITTERS, f.emitters},
                                   {SPEC_MOTION_BLUR, f.motion_blur}};
  if (f.punctual) s.push_back({SPEC_PUNCTUAL, VK_TRUE});
  scene.add_spec(s);
  return s;
}

}  // namespace

struct PathTracer::Variant {
  gpu::ComputePipeline pipeline;
  gpu::DescriptorSet set;
  Variant(const SharedResources& s, Features f)
      : pipeline(s.ctx, s.scene.shader("path_trace"), path_trace_bindings(s.scene), spec(s.scene, f),
                 sizeof(gpu::GpuDispatchConstants)),
        set(s.ctx, pipeline) {
    s.scene.bind(set, /*with_lights=*/true);
    set.bind_buffer(BINDING_FRAME, s.constants);
    set.bind_buffer(BINDING_COUNTERS, s.counters);
    set.bind_buffer(BINDING_ACCUM, s.accum);
  }
};

PathTracer::PathTracer(const SharedResources& shared, uint32_t width, uint32_t height, uint32_t spp,
                       uint32_t samples_per_dispatch)
    : shared_(shared), width_(width), height_(height), spp_(spp), samples_per_dispatch_(samples_per_dispatch) {}

PathTracer::~PathTracer() = default;

void PathTracer::record(VkCommandBuffer cmd, gpu::PassTimer& timer, const MethodFrame& f) {
  const bool blur = f.frame.camera_open.has_value();
  const bool lens = f.frame.camera.aperture > 0.0f || (blur && f.frame.camera_open->aperture > 0.0f);
  Features features{lens, f.env_nee, shared_.scene.has_emitters(), blur, shared_.scene.has_punctual()};
  auto& v = variants_[features.key()];
  if (!v) v = std::make_unique<Variant>(shared_, features);
  last_variant_ = std::to_string(shared_.scene.emitter_count()) + " emissive triangles" +
                  (features.punctual ? " + " + std::to_string(shared_.scene.light_count()) + " punctual lights" : "") +
                  (features.env_nee ? " + environment" : "") + (features.thin_lens ? ", thin lens" : ", pinhole") +
                  (features.motion_blur ? ", motion blur" : "");
  timer.begin(cmd, "path_trace");
  for (uint32_t done = 0; done < spp_; done += samples_per_dispatch_) {
    gpu::GpuDispatchConstants d{uint32_t(f.sample_base) + done, std::min(samples_per_dispatch_, spp_ - done)};
    gpu::dispatch_2d(cmd, v->pipeline, v->set, width_, height_, &d, sizeof d);
    gpu::compute_barrier(cmd);
  }
  timer.end(cmd);
}

std::vector<PassDecision> PathTracer::decisions() const {
  return {{"path_trace", true, "method pt: NEE over " + last_variant_},
          {"primary", false, "method pt has no reuse"},
          {"domain_init", false, "method pt has no reuse"},
          {"initial", false, "method pt has no reuse"},
          {"temporal", false, "method pt has no reuse"},
          {"spatial", false, "method pt has no reuse"},
          {"shade", false, "path_trace writes radiance directly"}};
}

}  // namespace strata::render
