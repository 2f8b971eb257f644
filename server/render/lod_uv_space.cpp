#include "render/lod_uv_space.h"

#include <algorithm>
#include <map>
#include <stdexcept>

#include <glm/gtc/matrix_transform.hpp>
#include <glm/gtc/type_ptr.hpp>

namespace strata::render {
namespace {

constexpr VkBufferUsageFlags k_build_input =
    gpu::k_storage_usage | VK_BUFFER_USAGE_ACCELERATION_STRUCTURE_BUILD_INPUT_READ_ONLY_BIT_KHR;

bool is_group(const scene::Instance& inst) { return inst.lod_meshes.size() > 1; }

}  // namespace

bool LodUvSpace::needed(const scene::Scene& scene) { return std::any_of(scene.instances.begin(), scene.instances.end(), is_group); }

LodUvSpace::LodUvSpace(const gpu::Context& ctx, const scene::Scene& scene, const std::vector<uint32_t>& mesh_primitive_base)
    : instances_(uint32_t(scene.instances.size())) {
  // Every LoD mesh's triangles at their UVs, z = 0 (the plane's translation puts them in place).
  std::vector<glm::vec3> uv_vertices;
  std::vector<uint32_t> uv_indices;
  struct Range { uint32_t vertex_offset, vertex_count, index_offset, triangle_count; };
  std::map<uint32_t, std::vector<Range>> ranges;  // per LoD mesh
  for (const auto& inst : scene.instances) {
    if (!is_group(inst)) continue;
    for (size_t l = 0; l < inst.lod_meshes.size() && l < gpu::LOD_MAX_LEVELS; ++l) {
      const uint32_t mesh = inst.lod_meshes[l];
      if (ranges.count(mesh)) continue;
      auto& r = ranges[mesh];
      for (const auto& p : scene.meshes[mesh].primitives) {
        r.push_back({uint32_t(uv_vertices.size()), uint32_t(p.uvs.size()), uint32_t(uv_indices.size()), uint32_t(p.triangle_count())});
        for (const auto& uv : p.uvs) uv_vertices.emplace_back(uv, 0.0f);
        uv_indices.insert(uv_indices.end(), p.indices.begin(), p.indices.end());
      }
    }
  }
  vertices_ = gpu::make_buffer<glm::vec3>(ctx, uv_vertices, k_build_input, gpu::Memory::Device, "lod uv vertices");
  indices_ = gpu::make_buffer<uint32_t>(ctx, uv_indices, k_build_input, gpu::Memory::Device, "lod uv indices");
  std::map<uint32_t, size_t> blas_of;  // LoD mesh -> its UV BLAS
  for (const auto& [mesh, rs] : ranges) {
    std::vector<gpu::BlasTriangles> geoms;
    for (const auto& r : rs)
      geoms.push_back({vertices_.address() + VkDeviceAddress(r.vertex_offset) * sizeof(glm::vec3), r.vertex_count,
                       uint32_t(sizeof(glm::vec3)), indices_.address() + VkDeviceAddress(r.index_offset) * sizeof(uint32_t),
                       r.triangle_count});
    blas_of[mesh] = blas_.size();
    blas_.emplace_back(ctx, geoms);
  }

  // A plane per LoD group; an instance per (group, level) with mask 1 << level.
  std::vector<VkAccelerationStructureInstanceKHR> tlas_instances;
  std::vector<gpu::GpuLodInstance> entries(scene.instances.size(), gpu::GpuLodInstance{});
  for (size_t i = 0; i < scene.instances.size(); ++i) {
    const auto& inst = scene.instances[i];
    if (!is_group(inst)) continue;
    auto& e = entries[i];
    e.uv_plane = planes_++;
    e.levels = uint32_t(std::min<size_t>(inst.lod_meshes.size(), gpu::LOD_MAX_LEVELS));
    const glm::mat4 plane = glm::translate(glm::mat4(1.0f), glm::vec3(0.0f, 0.0f, 2.0f * float(e.uv_plane)));
    for (uint32_t l = 0; l < e.levels; ++l) {
      const uint32_t mesh = inst.lod_meshes[l];
      e.primitive_base[l] = mesh_primitive_base.at(mesh);
      VkAccelerationStructureInstanceKHR vi{};
      vi.transform = gpu::to_vk_transform(glm::value_ptr(plane));
      vi.instanceCustomIndex = uint32_t(i) & 0xFFFFFFu;
      vi.mask = uint8_t(1u << l);
      vi.flags = VK_GEOMETRY_INSTANCE_TRIANGLE_FACING_CULL_DISABLE_BIT_KHR;
      vi.accelerationStructureReference = blas_[blas_of.at(mesh)].address();
      tlas_instances.push_back(vi);
    }
  }
  tlas_ = std::make_unique<gpu::Tlas>(ctx, uint32_t(tlas_instances.size()));
  ctx.submit_and_wait([&](VkCommandBuffer cmd) { tlas_->record_build(cmd, tlas_instances, false); });

  table_ = gpu::Buffer(ctx, sizeof(gpu::GpuLodHeader) + sizeof(gpu::GpuLodInstance) * std::max<size_t>(1, entries.size()),
                       gpu::k_storage_usage, gpu::Memory::Host, "lod table");
  table_.upload(entries.data(), sizeof(gpu::GpuLodInstance) * entries.size(), sizeof(gpu::GpuLodHeader));
  set_settings({});
}

void LodUvSpace::set_settings(const LodMappingSettings& s) {
  const gpu::GpuLodHeader h{s.uv ? gpu::LOD_MODE_UV : gpu::LOD_MODE_OFF, s.matching ? 1u : 0u, s.vertices, instances_};
  table_.upload(&h, sizeof h, 0);
}

VkDeviceSize LodUvSpace::bytes() const {
  VkDeviceSize b = vertices_.size() + indices_.size() + table_.size() + tlas_->bytes() + tlas_->scratch_bytes();
  for (const auto& blas : blas_) b += blas.bytes();
  return b;
}

}  // namespace strata::render
