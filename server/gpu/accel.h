#pragma once
// Acceleration structures: one BLAS per mesh LoD level (one geometry per primitive) and a TLAS that
// is rebuilt when the instance set or a BLAS reference changes and refitted when only transforms do.
#include <cstdint>
#include <span>
#include <vector>

#include "gpu/buffer.h"

namespace strata::gpu {

struct BlasTriangles {
  VkDeviceAddress vertices = 0;  // float3 positions at `vertex_stride`
  uint32_t vertex_count = 0;
  uint32_t vertex_stride = 0;
  VkDeviceAddress indices = 0;   // uint32 triangle list
  uint32_t triangle_count = 0;
  // Off for alpha-tested primitives (alphaMode MASK or BLEND): their triangles are reported to a ray
  // query as candidates, which the scene bridge confirms after the alpha test.
  bool opaque = true;
};

class AccelerationStructure {
 public:
  AccelerationStructure() = default;
  ~AccelerationStructure();
  AccelerationStructure(AccelerationStructure&& o) noexcept;
  AccelerationStructure& operator=(AccelerationStructure&& o) noexcept;
  AccelerationStructure(const AccelerationStructure&) = delete;
  AccelerationStructure& operator=(const AccelerationStructure&) = delete;

  VkAccelerationStructureKHR handle() const { return handle_; }
  VkDeviceAddress address() const { return address_; }
  VkDeviceSize bytes() const { return storage_.size(); }

 protected:
  void create(const Context& ctx, VkAccelerationStructureTypeKHR type, VkDeviceSize size, const char* name);
  void release();
  const Context* ctx_ = nullptr;
  Buffer storage_;
  VkAccelerationStructureKHR handle_ = VK_NULL_HANDLE;
  VkDeviceAddress address_ = 0;
};

class Blas : public AccelerationStructure {
 public:
  Blas() = default;
  // Builds on the device and waits; `geometries` must stay valid during the call only.
  Blas(const Context& ctx, std::span<const BlasTriangles> geometries);
};

// The BLAS of a deforming mesh: its vertices move every frame (render/scene_deform.h), so it is
// built once allowing updates and then refit (the same triangles, new positions) or rebuilt, each
// recorded into the frame's command buffer after the pass that wrote the vertices.
class DeformingBlas : public AccelerationStructure {
 public:
  DeformingBlas() = default;
  // Builds on the device and waits, from the vertices as they are now.
  DeformingBlas(const Context& ctx, std::span<const BlasTriangles> geometries);
  // Records a refit (`rebuild` false) or a full build from the current vertices, then a barrier
  // that makes it visible to the TLAS build and to compute shaders.
  void record_update(VkCommandBuffer cmd, bool rebuild);
  uint32_t refits() const { return refits_; }
  uint32_t rebuilds() const { return rebuilds_; }

 private:
  void record(VkCommandBuffer cmd, bool update);
  std::vector<BlasTriangles> geometries_;
  Buffer scratch_;
  VkDeviceSize scratch_alignment_ = 256;
  uint32_t refits_ = 0;
  uint32_t rebuilds_ = 0;
};

class Tlas : public AccelerationStructure {
 public:
  explicit Tlas(const Context& ctx, uint32_t max_instances);
  // Records the build into `cmd`: a refit (update) when `refit` and the previous build had the same
  // instance count, else a full build. Followed by a barrier that makes it visible to compute shaders.
  void record_build(VkCommandBuffer cmd, std::span<const VkAccelerationStructureInstanceKHR> instances, bool refit);
  uint32_t max_instances() const { return max_instances_; }
  uint32_t builds() const { return builds_; }
  uint32_t refits() const { return refits_; }
  VkDeviceSize scratch_bytes() const { return scratch_.size(); }

 private:
  uint32_t max_instances_ = 0;
  uint32_t built_count_ = UINT32_MAX;
  uint32_t builds_ = 0;
  uint32_t refits_ = 0;
  Buffer instances_;
  Buffer scratch_;
  VkDeviceSize scratch_alignment_ = 256;
};

// Row-major 3x4 for VkTransformMatrixKHR from a column-major glm-style 4x4 (16 floats).
VkTransformMatrixKHR to_vk_transform(const float* column_major_4x4);

}  // namespace strata::gpu
