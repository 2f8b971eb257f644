#include "render/splat_temporal.h"

#include "include/bindings.h"
#include "include/frame_data.h"
#include "restir/splat_data.h"

namespace strata::render {
namespace {

constexpr VkDescriptorType k_storage = VK_DESCRIPTOR_TYPE_STORAGE_BUFFER;
constexpr VkDescriptorType k_uniform = VK_DESCRIPTOR_TYPE_UNIFORM_BUFFER;

gpu::Buffer storage(const gpu::Context& ctx, size_t bytes, const char* name) {
  return gpu::Buffer(ctx, bytes, gpu::k_storage_usage, gpu::Memory::Device, name);
}

}  // namespace

// One pass: its pipeline and a descriptor set per frame parity.
struct SplatTemporal::Pass {
  gpu::ComputePipeline pipeline;
  std::array<std::unique_ptr<gpu::DescriptorSet>, 2> sets;
  Pass(const gpu::Context& ctx, const char* shader, std::vector<gpu::Binding> bindings)
      : pipeline(ctx, shader, bindings, std::vector<gpu::SpecConstant>{}, 0) {
    for (auto& s : sets) s = std::make_unique<gpu::DescriptorSet>(ctx, pipeline);
  }
};

SplatTemporal::SplatTemporal(const SharedResources& shared, uint32_t width, uint32_t height, const gpu::Buffer& restir_constants,
                             const gpu::Buffer& work, const std::array<gpu::Buffer, 2>& history, const gpu::Buffer& contribution)
    : shared_(shared), width_(width), height_(height) {
  const auto& ctx = shared.ctx;
  const size_t pixels = size_t(width) * height;
  count_ = storage(ctx, sizeof(uint32_t) * pixels, "splat counts");
  offsets_ = storage(ctx, sizeof(uint32_t) * (pixels + 1), "splat offsets");

  // The ReSTIR passes' common bindings (restir_pass.glsl) with the scene and its history.
  auto restir = [](std::vector<gpu::Binding> extra) {
    auto b = GpuScene::bindings(/*with_lights=*/false, /*with_history=*/true);
    for (auto x : {BINDING_FRAME, BINDING_RESTIR}) b.push_back({uint32_t(x), k_uniform});
    for (auto x : {BINDING_COUNTERS, BINDING_RESERVOIRS_OUT, BINDING_CONTRIBUTION, BINDING_RESERVOIRS_IN}) b.push_back({uint32_t(x), k_storage});
    b.insert(b.end(), extra.begin(), extra.end());
    return b;
  };
  project_ = std::make_unique<Pass>(ctx, "restir_splat_project",
                                    restir({{BINDING_SPLATS, k_storage}, {BINDING_SPLAT_TARGET, k_storage}, {BINDING_SPLAT_COUNT, k_storage}}));
  scan_ = std::make_unique<Pass>(ctx, "restir_splat_scan",
                                 std::vector<gpu::Binding>{{BINDING_FRAME, k_uniform}, {BINDING_SPLAT_COUNT, k_storage}, {BINDING_SPLAT_OFFSETS, k_storage}});
  insert_ = std::make_unique<Pass>(ctx, "restir_splat_insert",
                                   std::vector<gpu::Binding>{{BINDING_FRAME, k_uniform},
                                                             {BINDING_SPLAT_TARGET, k_storage},
                                                             {BINDING_SPLAT_COUNT, k_storage},
                                                             {BINDING_SPLAT_OFFSETS, k_storage},
                                                             {BINDING_SPLAT_LIST, k_storage}});
  resample_ = std::make_unique<Pass>(ctx, "restir_splat_resample",
                                     restir({{BINDING_SPLATS, k_storage}, {BINDING_SPLAT_OFFSETS, k_storage}, {BINDING_SPLAT_LIST, k_storage}}));

  for (int parity = 0; parity < 2; ++parity) {
    const gpu::Buffer& previous = history[size_t(1 - parity)];
    for (Pass* p : {project_.get(), resample_.get()}) {
      auto& set = *p->sets[size_t(parity)];
      shared.scene.bind(set, /*with_lights=*/false, /*with_history=*/true, parity);
      set.bind_buffer(BINDING_FRAME, shared.constants);
      set.bind_buffer(BINDING_RESTIR, restir_constants);
      set.bind_buffer(BINDING_COUNTERS, shared.counters);
      set.bind_buffer(BINDING_RESERVOIRS_OUT, work);
      set.bind_buffer(BINDING_CONTRIBUTION, contribution);
      set.bind_buffer(BINDING_RESERVOIRS_IN, previous);
    }
    project_->sets[size_t(parity)]->bind_buffer(BINDING_SPLAT_COUNT, count_);
    resample_->sets[size_t(parity)]->bind_buffer(BINDING_SPLAT_OFFSETS, offsets_);
    auto& sc = *scan_->sets[size_t(parity)];
    sc.bind_buffer(BINDING_FRAME, shared.constants);
    sc.bind_buffer(BINDING_SPLAT_COUNT, count_);
    sc.bind_buffer(BINDING_SPLAT_OFFSETS, offsets_);
    auto& in = *insert_->sets[size_t(parity)];
    in.bind_buffer(BINDING_FRAME, shared.constants);
    in.bind_buffer(BINDING_SPLAT_COUNT, count_);
    in.bind_buffer(BINDING_SPLAT_OFFSETS, offsets_);
  }
  ensure_partitions(1);
}

void SplatTemporal::ensure_partitions(uint32_t partitions) {
  if (partitions <= partitions_) return;
  // Records, targets and the list grow with K (multi-splatting, RS-main Eq. 19) the first time a
  // frame's shutter needs it: a session that never opens the shutter keeps one partition.
  partitions_ = partitions;
  const auto& ctx = shared_.ctx;
  const size_t records = size_t(width_) * height_ * partitions;
  splats_ = storage(ctx, sizeof(gpu::SplatRecord) * records, "splats");
  target_ = storage(ctx, sizeof(uint32_t) * records, "splat targets");
  list_ = storage(ctx, sizeof(uint32_t) * records, "splat list");
  for (size_t parity = 0; parity < 2; ++parity) {
    for (Pass* p : {project_.get(), resample_.get()}) p->sets[parity]->bind_buffer(BINDING_SPLATS, splats_);
    project_->sets[parity]->bind_buffer(BINDING_SPLAT_TARGET, target_);
    resample_->sets[parity]->bind_buffer(BINDING_SPLAT_LIST, list_);
    insert_->sets[parity]->bind_buffer(BINDING_SPLAT_TARGET, target_);
    insert_->sets[parity]->bind_buffer(BINDING_SPLAT_LIST, list_);
  }
}

SplatTemporal::~SplatTemporal() = default;

void SplatTemporal::record(VkCommandBuffer cmd, gpu::PassTimer& timer, int parity, uint32_t partitions) {
  const size_t p = size_t(parity);
  ensure_partitions(partitions);
  timer.begin(cmd, "splat_project");
  vkCmdFillBuffer(cmd, count_.handle(), 0, VK_WHOLE_SIZE, 0);
  gpu::compute_barrier(cmd);
  // One layer per time partition; the shader's splat_partitions() is the same number.
  gpu::dispatch_layers(cmd, project_->pipeline, *project_->sets[p], width_, height_, partitions);
  gpu::compute_barrier(cmd);
  timer.end(cmd);
  timer.begin(cmd, "splat_scan");
  gpu::dispatch_1d(cmd, scan_->pipeline, *scan_->sets[p], 1);
  gpu::compute_barrier(cmd);
  timer.end(cmd);
  timer.begin(cmd, "splat_insert");
  gpu::dispatch_layers(cmd, insert_->pipeline, *insert_->sets[p], width_, height_, partitions);
  gpu::compute_barrier(cmd);
  timer.end(cmd);
  timer.begin(cmd, "splat_resample");
  gpu::dispatch_2d(cmd, resample_->pipeline, *resample_->sets[p], width_, height_);
  gpu::compute_barrier(cmd);
  timer.end(cmd);
}

std::map<std::string, uint64_t> SplatTemporal::memory_bytes() const {
  return {{"splats", splats_.size() + target_.size() + count_.size() + offsets_.size() + list_.size()}};
}

}  // namespace strata::render
