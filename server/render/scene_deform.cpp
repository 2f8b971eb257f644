#include "render/scene_deform.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include "include/bindings.h"
#include "render/pass.h"

namespace strata::render {
namespace {

using Box = std::pair<glm::vec3, glm::vec3>;

Box empty_box() {
  return {glm::vec3(std::numeric_limits<float>::max()), glm::vec3(-std::numeric_limits<float>::max())};
}

void grow(Box& b, glm::vec3 p) {
  b.first = glm::min(b.first, p);
  b.second = glm::max(b.second, p);
}

double surface_area(const Box& b) {
  const glm::dvec3 d = glm::max(glm::dvec3(b.second) - glm::dvec3(b.first), glm::dvec3(0.0));
  return 2.0 * (d.x * d.y + d.y * d.z + d.z * d.x);
}

// Barrier: the deformation pass's vertex writes before the BLAS builds read them.
void vertices_to_blas_barrier(VkCommandBuffer cmd) {
  VkMemoryBarrier2 mb{VK_STRUCTURE_TYPE_MEMORY_BARRIER_2};
  mb.srcStageMask = VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT;
  mb.srcAccessMask = VK_ACCESS_2_SHADER_WRITE_BIT;
  mb.dstStageMask = VK_PIPELINE_STAGE_2_ACCELERATION_STRUCTURE_BUILD_BIT_KHR | VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT;
  mb.dstAccessMask = VK_ACCESS_2_SHADER_READ_BIT | VK_ACCESS_2_ACCELERATION_STRUCTURE_READ_BIT_KHR;
  VkDependencyInfo dep{VK_STRUCTURE_TYPE_DEPENDENCY_INFO};
  dep.memoryBarrierCount = 1;
  dep.pMemoryBarriers = &mb;
  vkCmdPipelineBarrier2(cmd, &dep);
}

}  // namespace

bool SceneDeformation::needed(const scene::Scene& scene) {
  return std::any_of(scene.instances.begin(), scene.instances.end(), [](const scene::Instance& i) { return i.deforms(); });
}

std::vector<uint32_t> SceneDeformation::copied_meshes(const scene::Scene& scene, uint32_t slots) {
  std::vector<uint32_t> meshes;
  for (const scene::Instance& inst : scene.instances)
    if (inst.deforms())
      for (uint32_t s = 0; s < slots; ++s) meshes.push_back(inst.lod_meshes.front());
  return meshes;
}

SceneDeformation::SceneDeformation(const gpu::Context& ctx, const scene::Scene& scene, uint32_t slots, const Layout& layout,
                                   const gpu::Buffer& vertices)
    : scene_(scene), copy_of_(scene.instances.size(), -1), slots_(slots) {
  std::array<std::vector<gpu::GpuDeformJob>, 2> jobs;
  // Per deformed vertex of a slot, its job and vertex: the same for every slot, whose jobs come in
  // the same order.
  std::vector<glm::uvec2> vertex_job;
  std::vector<gpu::GpuMorphDelta> deltas;
  std::vector<gpu::GpuSkinVertex> skin;
  size_t copy = 0;
  for (size_t i = 0; i < scene.instances.size(); ++i) {
    const scene::Instance& inst = scene.instances[i];
    if (!inst.deforms()) continue;
    copy_of_[i] = int(copy);
    const uint32_t mesh_index = inst.lod_meshes.front();
    const scene::Mesh& mesh = scene.meshes[mesh_index];
    Instance d;
    d.joint_offset = joint_count_;
    d.weight_offset = weight_count_;
    const size_t joints = inst.skin >= 0 ? scene.skins[size_t(inst.skin)].inverse_bind.size() : 0;
    d.joint_boxes.assign(std::max<size_t>(joints, 1), empty_box());
    d.target_reach.assign(inst.morph_weights.size(), glm::vec3(0.0f));
    // The rest vertices of every primitive, their skin and morph targets, once for all slots.
    uint32_t src = layout.mesh_vertex_base[mesh_index];
    std::vector<gpu::GpuDeformJob> prim_jobs;
    for (const scene::Primitive& p : mesh.primitives) {
      gpu::GpuDeformJob job{};
      job.src_vertex = src;
      job.vertex_count = uint32_t(p.positions.size());
      job.morph_offset = uint32_t(deltas.size());
      job.target_count = uint32_t(std::min(p.targets.size(), inst.morph_weights.size()));
      job.weight_offset = d.weight_offset;
      job.skin_offset = gpu::DEFORM_NOT_SKINNED;
      job.joint_offset = d.joint_offset;
      for (uint32_t t = 0; t < job.target_count; ++t) {
        const scene::MorphTarget& target = p.targets[t];
        for (size_t v = 0; v < p.positions.size(); ++v) {
          const glm::vec3 dn = target.normals.empty() ? glm::vec3(0.0f) : target.normals[v];
          deltas.push_back({glm::vec4(target.positions[v], 0.0f), glm::vec4(dn, 0.0f)});
          d.target_reach[t] = glm::max(d.target_reach[t], glm::abs(target.positions[v]));
        }
      }
      const bool skinned = joints > 0 && !p.joints.empty();
      if (skinned) {
        job.skin_offset = uint32_t(skin.size());
        for (size_t v = 0; v < p.positions.size(); ++v) skin.push_back({p.joints[v], p.weights[v]});
      }
      for (size_t v = 0; v < p.positions.size(); ++v) {
        if (!skinned) {
          grow(d.joint_boxes[0], p.positions[v]);
          continue;
        }
        for (int k = 0; k < 4; ++k)
          if (p.weights[v][k] != 0.0f) grow(d.joint_boxes[p.joints[v][k]], p.positions[v]);
      }
      prim_jobs.push_back(job);
      src += job.vertex_count;
    }
    joint_count_ += uint32_t(joints);
    weight_count_ += uint32_t(inst.morph_weights.size());
    for (uint32_t s = 0; s < slots; ++s, ++copy) {
      uint32_t dst = layout.copy_vertex_base[copy];
      for (gpu::GpuDeformJob job : prim_jobs) {
        job.dst_vertex = dst;
        dst += job.vertex_count;
        if (s == 0)
          for (uint32_t v = 0; v < job.vertex_count; ++v) vertex_job.push_back({uint32_t(jobs[s].size()), v});
        jobs[s].push_back(job);
      }
      primitive_base_.push_back(layout.copy_primitive_base[copy]);
      vertex_base_.push_back(layout.copy_vertex_base[copy]);
      blas_.emplace_back(ctx, layout.copy_geometries[copy]);
      built_area_.push_back(0.0);
    }
    instances_.push_back(std::move(d));
  }
  vertices_per_slot_ = uint32_t(vertex_job.size());
  const auto usage = gpu::k_storage_usage;
  for (uint32_t s = 0; s < 2; ++s) {
    const uint32_t from = std::min(s, slots - 1);
    jobs_[s] = gpu::make_buffer<gpu::GpuDeformJob>(ctx, jobs[from], usage, gpu::Memory::Device, "deform jobs");
    matrices_[s] = gpu::Buffer(ctx, std::max<size_t>(1, joint_count_) * sizeof(gpu::GpuSkinMatrix), usage, gpu::Memory::Host,
                               "skinning matrices");
    weights_[s] = gpu::Buffer(ctx, std::max<size_t>(1, weight_count_) * sizeof(float), usage, gpu::Memory::Host, "morph weights");
  }
  vertex_job_ = gpu::make_buffer<glm::uvec2>(ctx, vertex_job, usage, gpu::Memory::Device, "deformed vertex jobs");
  if (deltas.empty()) deltas.push_back({});
  if (skin.empty()) skin.push_back({});
  morph_deltas_ = gpu::make_buffer<gpu::GpuMorphDelta>(ctx, deltas, usage, gpu::Memory::Device, "morph deltas");
  skin_vertices_ = gpu::make_buffer<gpu::GpuSkinVertex>(ctx, skin, usage, gpu::Memory::Device, "skin vertices");
  pass_ = std::make_unique<Pass>(
      ctx, nullptr, SceneUse{}, "deform",
      std::vector<PassResource>{
          {BINDING_VERTICES, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER, Access::read_write, [&vertices](int) -> const gpu::Buffer& { return vertices; }},
          {BINDING_DEFORM_JOBS, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER, Access::read, [this](int p) -> const gpu::Buffer& { return jobs_[size_t(p & 1)]; }},
          storage(BINDING_DEFORM_VERTEX_JOB, Access::read, vertex_job_),
          storage(BINDING_MORPH_DELTAS, Access::read, morph_deltas_),
          storage(BINDING_SKIN_VERTICES, Access::read, skin_vertices_),
          {BINDING_SKIN_MATRICES, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER, Access::read, [this](int p) -> const gpu::Buffer& { return matrices_[size_t(p & 1)]; }},
          {BINDING_MORPH_WEIGHTS, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER, Access::read, [this](int p) -> const gpu::Buffer& { return weights_[size_t(p & 1)]; }}},
      std::vector<gpu::SpecConstant>{}, uint32_t(sizeof(uint32_t)));
}

SceneDeformation::~SceneDeformation() = default;

uint32_t SceneDeformation::primitive_base(size_t instance, int slot) const {
  return primitive_base_[size_t(copy_of_[instance]) + size_t(slot) % slots_];
}

uint32_t SceneDeformation::vertex_base(size_t instance, int slot) const {
  return vertex_base_[size_t(copy_of_[instance]) + size_t(slot) % slots_];
}

VkDeviceAddress SceneDeformation::blas_address(size_t instance, int slot) const {
  return blas_[size_t(copy_of_[instance]) + size_t(slot) % slots_].address();
}

void SceneDeformation::record(VkCommandBuffer cmd, int slot, const scene::FrameState& frame) {
  std::vector<gpu::GpuSkinMatrix> matrices(std::max<size_t>(1, joint_count_));
  std::vector<float> weights(std::max<size_t>(1, weight_count_), 0.0f);
  std::vector<std::vector<scene::SkinningMatrix>> skinning(instances_.size());  // per deforming instance, for its bounds below
  for (size_t i = 0; i < scene_.instances.size(); ++i) {
    if (copy_of_[i] < 0) continue;
    const size_t d = size_t(copy_of_[i]) / slots_;
    const Instance& di = instances_[d];
    skinning[d] = scene::instance_skinning(scene_, frame, i);
    for (size_t j = 0; j < skinning[d].size(); ++j)
      matrices[di.joint_offset + j] = {skinning[d][j].position, glm::mat4(skinning[d][j].normal)};
    const auto w = scene::morph_weights_at(scene_, frame, i);
    std::copy_n(w.begin(), std::min(w.size(), scene_.instances[i].morph_weights.size()), weights.begin() + di.weight_offset);
  }
  const size_t s = size_t(slot) % slots_;
  matrices_[s].upload(matrices.data(), matrices.size() * sizeof(gpu::GpuSkinMatrix));
  weights_[s].upload(weights.data(), weights.size() * sizeof(float));
  pass_->dispatch_1d(cmd, int(s), vertices_per_slot_, &vertices_per_slot_);
  vertices_to_blas_barrier(cmd);
  for (size_t i = 0; i < scene_.instances.size(); ++i) {
    if (copy_of_[i] < 0) continue;
    const size_t c = size_t(copy_of_[i]) + s;
    const double area = surface_area(bounds(i, scene::morph_weights_at(scene_, frame, i), skinning[size_t(copy_of_[i]) / slots_]));
    const bool rebuild = !(area <= k_rebuild_growth * built_area_[c]);
    blas_[c].record_update(cmd, rebuild);
    if (rebuild) built_area_[c] = area;
  }
}

std::pair<glm::vec3, glm::vec3> SceneDeformation::object_bounds(size_t instance, const scene::FrameState& frame) const {
  return bounds(instance, scene::morph_weights_at(scene_, frame, instance), scene::instance_skinning(scene_, frame, instance));
}

std::pair<glm::vec3, glm::vec3> SceneDeformation::bounds(size_t instance, std::span<const float> w,
                                                         std::span<const scene::SkinningMatrix> s) const {
  const Instance& di = instances_[size_t(copy_of_[instance]) / slots_];
  glm::vec3 reach(0.0f);
  for (size_t t = 0; t < di.target_reach.size() && t < w.size(); ++t) reach += std::abs(w[t]) * di.target_reach[t];
  if (scene_.instances[instance].skin < 0) return {di.joint_boxes[0].first - reach, di.joint_boxes[0].second + reach};
  Box out = empty_box();
  for (size_t j = 0; j < di.joint_boxes.size() && j < s.size(); ++j) {
    const Box& b = di.joint_boxes[j];
    if (b.first.x > b.second.x) continue;  // no vertex follows this joint
    for (int c = 0; c < 8; ++c) {
      const glm::vec3 corner((c & 1) ? b.second.x + reach.x : b.first.x - reach.x, (c & 2) ? b.second.y + reach.y : b.first.y - reach.y,
                             (c & 4) ? b.second.z + reach.z : b.first.z - reach.z);
      grow(out, glm::vec3(s[j].position * glm::vec4(corner, 1.0f)));
    }
  }
  return out;
}

uint32_t SceneDeformation::refits() const {
  uint32_t n = 0;
  for (const auto& b : blas_) n += b.refits();
  return n;
}

uint32_t SceneDeformation::rebuilds() const {
  uint32_t n = 0;
  for (const auto& b : blas_) n += b.rebuilds();
  return n;
}

uint64_t SceneDeformation::bytes() const {
  uint64_t n = vertex_job_.size() + morph_deltas_.size() + skin_vertices_.size();
  for (size_t s = 0; s < 2; ++s) n += jobs_[s].size() + matrices_[s].size() + weights_[s].size();
  for (const auto& b : blas_) n += b.bytes();
  return n;
}

}  // namespace strata::render
