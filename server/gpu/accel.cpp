#include "gpu/accel.h"

#include <algorithm>
#include <cstring>
#include <utility>

namespace strata::gpu {
namespace {

VkDeviceSize align_up(VkDeviceSize v, VkDeviceSize a) { return (v + a - 1) / a * a; }

VkDeviceSize scratch_alignment(const Context& ctx) {
  VkPhysicalDeviceAccelerationStructurePropertiesKHR as{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_ACCELERATION_STRUCTURE_PROPERTIES_KHR};
  VkPhysicalDeviceProperties2 p2{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_PROPERTIES_2, &as};
  vkGetPhysicalDeviceProperties2(ctx.physical_device(), &p2);
  return std::max<VkDeviceSize>(as.minAccelerationStructureScratchOffsetAlignment, 1);
}

constexpr VkBufferUsageFlags k_scratch_usage = VK_BUFFER_USAGE_STORAGE_BUFFER_BIT | VK_BUFFER_USAGE_SHADER_DEVICE_ADDRESS_BIT;

void as_barrier(VkCommandBuffer cmd) {
  VkMemoryBarrier2 mb{VK_STRUCTURE_TYPE_MEMORY_BARRIER_2};
  mb.srcStageMask = VK_PIPELINE_STAGE_2_ACCELERATION_STRUCTURE_BUILD_BIT_KHR;
  mb.srcAccessMask = VK_ACCESS_2_ACCELERATION_STRUCTURE_WRITE_BIT_KHR;
  mb.dstStageMask = VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT | VK_PIPELINE_STAGE_2_ACCELERATION_STRUCTURE_BUILD_BIT_KHR;
  mb.dstAccessMask = VK_ACCESS_2_ACCELERATION_STRUCTURE_READ_BIT_KHR | VK_ACCESS_2_ACCELERATION_STRUCTURE_WRITE_BIT_KHR;
  VkDependencyInfo dep{VK_STRUCTURE_TYPE_DEPENDENCY_INFO};
  dep.memoryBarrierCount = 1;
  dep.pMemoryBarriers = &mb;
  vkCmdPipelineBarrier2(cmd, &dep);
}

}  // namespace

AccelerationStructure::~AccelerationStructure() { release(); }

AccelerationStructure::AccelerationStructure(AccelerationStructure&& o) noexcept { *this = std::move(o); }

AccelerationStructure& AccelerationStructure::operator=(AccelerationStructure&& o) noexcept {
  if (this != &o) {
    release();
    ctx_ = std::exchange(o.ctx_, nullptr);
    storage_ = std::move(o.storage_);
    handle_ = std::exchange(o.handle_, VK_NULL_HANDLE);
    address_ = std::exchange(o.address_, 0);
  }
  return *this;
}

void AccelerationStructure::release() {
  if (ctx_ && handle_) ctx_->rt().destroy_as(ctx_->device(), handle_, nullptr);
  handle_ = VK_NULL_HANDLE;
}

void AccelerationStructure::create(const Context& ctx, VkAccelerationStructureTypeKHR type, VkDeviceSize size,
                                   const char* name) {
  ctx_ = &ctx;
  storage_ = Buffer(ctx, size, VK_BUFFER_USAGE_ACCELERATION_STRUCTURE_STORAGE_BIT_KHR | VK_BUFFER_USAGE_SHADER_DEVICE_ADDRESS_BIT,
                    Memory::Device, name);
  VkAccelerationStructureCreateInfoKHR ci{VK_STRUCTURE_TYPE_ACCELERATION_STRUCTURE_CREATE_INFO_KHR};
  ci.buffer = storage_.handle();
  ci.size = size;
  ci.type = type;
  check(ctx.rt().create_as(ctx.device(), &ci, nullptr, &handle_), "vkCreateAccelerationStructureKHR");
  VkAccelerationStructureDeviceAddressInfoKHR ai{VK_STRUCTURE_TYPE_ACCELERATION_STRUCTURE_DEVICE_ADDRESS_INFO_KHR};
  ai.accelerationStructure = handle_;
  address_ = ctx.rt().get_as_address(ctx.device(), &ai);
}

namespace {

// The build description of a BLAS over `geometries` (they and the returned vectors must outlive its use).
struct BlasBuild {
  std::vector<VkAccelerationStructureGeometryKHR> geoms;
  std::vector<VkAccelerationStructureBuildRangeInfoKHR> ranges;
  std::vector<uint32_t> counts;
  VkAccelerationStructureBuildGeometryInfoKHR info{VK_STRUCTURE_TYPE_ACCELERATION_STRUCTURE_BUILD_GEOMETRY_INFO_KHR};
};

void describe_blas(std::span<const BlasTriangles> geometries, VkBuildAccelerationStructureFlagsKHR flags, BlasBuild& b) {
  if (geometries.empty()) throw GpuError("a BLAS needs at least one geometry");
  for (const auto& g : geometries) {
    VkAccelerationStructureGeometryKHR geom{VK_STRUCTURE_TYPE_ACCELERATION_STRUCTURE_GEOMETRY_KHR};
    geom.geometryType = VK_GEOMETRY_TYPE_TRIANGLES_KHR;
    geom.flags = g.opaque ? VkGeometryFlagsKHR(VK_GEOMETRY_OPAQUE_BIT_KHR) : VkGeometryFlagsKHR(0);
    auto& tri = geom.geometry.triangles;
    tri.sType = VK_STRUCTURE_TYPE_ACCELERATION_STRUCTURE_GEOMETRY_TRIANGLES_DATA_KHR;
    tri.vertexFormat = VK_FORMAT_R32G32B32_SFLOAT;
    tri.vertexData.deviceAddress = g.vertices;
    tri.vertexStride = g.vertex_stride;
    tri.maxVertex = g.vertex_count > 0 ? g.vertex_count - 1 : 0;
    tri.indexType = VK_INDEX_TYPE_UINT32;
    tri.indexData.deviceAddress = g.indices;
    b.geoms.push_back(geom);
    b.ranges.push_back({g.triangle_count, 0, 0, 0});
    b.counts.push_back(g.triangle_count);
  }
  b.info.type = VK_ACCELERATION_STRUCTURE_TYPE_BOTTOM_LEVEL_KHR;
  b.info.flags = flags;
  b.info.mode = VK_BUILD_ACCELERATION_STRUCTURE_MODE_BUILD_KHR;
  b.info.geometryCount = uint32_t(b.geoms.size());
  b.info.pGeometries = b.geoms.data();
}

constexpr VkBuildAccelerationStructureFlagsKHR k_deforming_flags =
    VK_BUILD_ACCELERATION_STRUCTURE_PREFER_FAST_TRACE_BIT_KHR | VK_BUILD_ACCELERATION_STRUCTURE_ALLOW_UPDATE_BIT_KHR;

}  // namespace

Blas::Blas(const Context& ctx, std::span<const BlasTriangles> geometries) {
  BlasBuild b;
  describe_blas(geometries, VK_BUILD_ACCELERATION_STRUCTURE_PREFER_FAST_TRACE_BIT_KHR, b);
  VkAccelerationStructureBuildSizesInfoKHR sizes{VK_STRUCTURE_TYPE_ACCELERATION_STRUCTURE_BUILD_SIZES_INFO_KHR};
  ctx.rt().get_build_sizes(ctx.device(), VK_ACCELERATION_STRUCTURE_BUILD_TYPE_DEVICE_KHR, &b.info, b.counts.data(), &sizes);
  create(ctx, VK_ACCELERATION_STRUCTURE_TYPE_BOTTOM_LEVEL_KHR, sizes.accelerationStructureSize, "blas");
  VkDeviceSize align = scratch_alignment(ctx);
  Buffer scratch(ctx, sizes.buildScratchSize + align, k_scratch_usage, Memory::Device, "blas scratch");
  b.info.dstAccelerationStructure = handle_;
  b.info.scratchData.deviceAddress = align_up(scratch.address(), align);
  const VkAccelerationStructureBuildRangeInfoKHR* range_ptr = b.ranges.data();
  ctx.submit_and_wait([&](VkCommandBuffer cmd) {
    ctx.rt().cmd_build_as(cmd, 1, &b.info, &range_ptr);
    as_barrier(cmd);
  });
}

DeformingBlas::DeformingBlas(const Context& ctx, std::span<const BlasTriangles> geometries)
    : geometries_(geometries.begin(), geometries.end()) {
  BlasBuild b;
  describe_blas(geometries_, k_deforming_flags, b);
  VkAccelerationStructureBuildSizesInfoKHR sizes{VK_STRUCTURE_TYPE_ACCELERATION_STRUCTURE_BUILD_SIZES_INFO_KHR};
  ctx.rt().get_build_sizes(ctx.device(), VK_ACCELERATION_STRUCTURE_BUILD_TYPE_DEVICE_KHR, &b.info, b.counts.data(), &sizes);
  create(ctx, VK_ACCELERATION_STRUCTURE_TYPE_BOTTOM_LEVEL_KHR, sizes.accelerationStructureSize, "deforming blas");
  scratch_alignment_ = scratch_alignment(ctx);
  scratch_ = Buffer(ctx, std::max(sizes.buildScratchSize, sizes.updateScratchSize) + scratch_alignment_, k_scratch_usage,
                    Memory::Device, "deforming blas scratch");
  ctx.submit_and_wait([&](VkCommandBuffer cmd) { record(cmd, false); });
}

void DeformingBlas::record_update(VkCommandBuffer cmd, bool rebuild) {
  record(cmd, !rebuild);
  (rebuild ? rebuilds_ : refits_)++;
}

void DeformingBlas::record(VkCommandBuffer cmd, bool update) {
  BlasBuild b;
  describe_blas(geometries_, k_deforming_flags, b);
  b.info.mode = update ? VK_BUILD_ACCELERATION_STRUCTURE_MODE_UPDATE_KHR : VK_BUILD_ACCELERATION_STRUCTURE_MODE_BUILD_KHR;
  b.info.srcAccelerationStructure = update ? handle_ : VK_NULL_HANDLE;
  b.info.dstAccelerationStructure = handle_;
  b.info.scratchData.deviceAddress = align_up(scratch_.address(), scratch_alignment_);
  const VkAccelerationStructureBuildRangeInfoKHR* range_ptr = b.ranges.data();
  ctx_->rt().cmd_build_as(cmd, 1, &b.info, &range_ptr);
  as_barrier(cmd);
}

Tlas::Tlas(const Context& ctx, uint32_t max_instances)
    : max_instances_(std::max(max_instances, 1u)),
      instances_(ctx, sizeof(VkAccelerationStructureInstanceKHR) * std::max(max_instances, 1u),
                 VK_BUFFER_USAGE_ACCELERATION_STRUCTURE_BUILD_INPUT_READ_ONLY_BIT_KHR | VK_BUFFER_USAGE_SHADER_DEVICE_ADDRESS_BIT,
                 Memory::Host, "tlas instances") {
  VkAccelerationStructureGeometryKHR geom{VK_STRUCTURE_TYPE_ACCELERATION_STRUCTURE_GEOMETRY_KHR};
  geom.geometryType = VK_GEOMETRY_TYPE_INSTANCES_KHR;
  geom.geometry.instances.sType = VK_STRUCTURE_TYPE_ACCELERATION_STRUCTURE_GEOMETRY_INSTANCES_DATA_KHR;
  VkAccelerationStructureBuildGeometryInfoKHR build{VK_STRUCTURE_TYPE_ACCELERATION_STRUCTURE_BUILD_GEOMETRY_INFO_KHR};
  build.type = VK_ACCELERATION_STRUCTURE_TYPE_TOP_LEVEL_KHR;
  build.flags = VK_BUILD_ACCELERATION_STRUCTURE_PREFER_FAST_TRACE_BIT_KHR | VK_BUILD_ACCELERATION_STRUCTURE_ALLOW_UPDATE_BIT_KHR;
  build.geometryCount = 1;
  build.pGeometries = &geom;
  VkAccelerationStructureBuildSizesInfoKHR sizes{VK_STRUCTURE_TYPE_ACCELERATION_STRUCTURE_BUILD_SIZES_INFO_KHR};
  ctx.rt().get_build_sizes(ctx.device(), VK_ACCELERATION_STRUCTURE_BUILD_TYPE_DEVICE_KHR, &build, &max_instances_, &sizes);
  create(ctx, VK_ACCELERATION_STRUCTURE_TYPE_TOP_LEVEL_KHR, sizes.accelerationStructureSize, "tlas");
  scratch_alignment_ = scratch_alignment(ctx);
  scratch_ = Buffer(ctx, std::max(sizes.buildScratchSize, sizes.updateScratchSize) + scratch_alignment_, k_scratch_usage,
                    Memory::Device, "tlas scratch");
}

void Tlas::record_build(VkCommandBuffer cmd, std::span<const VkAccelerationStructureInstanceKHR> instances, bool refit) {
  if (instances.size() > max_instances_) throw GpuError("TLAS holds at most " + std::to_string(max_instances_) + " instances");
  auto count = uint32_t(instances.size());
  instances_.upload(instances.data(), instances.size_bytes());
  VkAccelerationStructureGeometryKHR geom{VK_STRUCTURE_TYPE_ACCELERATION_STRUCTURE_GEOMETRY_KHR};
  geom.geometryType = VK_GEOMETRY_TYPE_INSTANCES_KHR;
  geom.flags = VK_GEOMETRY_OPAQUE_BIT_KHR;
  geom.geometry.instances.sType = VK_STRUCTURE_TYPE_ACCELERATION_STRUCTURE_GEOMETRY_INSTANCES_DATA_KHR;
  geom.geometry.instances.data.deviceAddress = instances_.address();
  bool update = refit && built_count_ == count;
  VkAccelerationStructureBuildGeometryInfoKHR build{VK_STRUCTURE_TYPE_ACCELERATION_STRUCTURE_BUILD_GEOMETRY_INFO_KHR};
  build.type = VK_ACCELERATION_STRUCTURE_TYPE_TOP_LEVEL_KHR;
  build.flags = VK_BUILD_ACCELERATION_STRUCTURE_PREFER_FAST_TRACE_BIT_KHR | VK_BUILD_ACCELERATION_STRUCTURE_ALLOW_UPDATE_BIT_KHR;
  build.mode = update ? VK_BUILD_ACCELERATION_STRUCTURE_MODE_UPDATE_KHR : VK_BUILD_ACCELERATION_STRUCTURE_MODE_BUILD_KHR;
  build.srcAccelerationStructure = update ? handle_ : VK_NULL_HANDLE;
  build.dstAccelerationStructure = handle_;
  build.geometryCount = 1;
  build.pGeometries = &geom;
  build.scratchData.deviceAddress = align_up(scratch_.address(), scratch_alignment_);
  VkAccelerationStructureBuildRangeInfoKHR range{count, 0, 0, 0};
  const VkAccelerationStructureBuildRangeInfoKHR* range_ptr = &range;
  ctx_->rt().cmd_build_as(cmd, 1, &build, &range_ptr);
  as_barrier(cmd);
  built_count_ = count;
  (update ? refits_ : builds_)++;
}

VkTransformMatrixKHR to_vk_transform(const float* m) {
  VkTransformMatrixKHR t{};
  for (int row = 0; row < 3; ++row)
    for (int col = 0; col < 4; ++col) t.matrix[row][col] = m[col * 4 + row];
  return t;
}

}  // namespace strata::gpu
