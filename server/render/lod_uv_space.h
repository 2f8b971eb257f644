#pragma once
// The UV-space acceleration structure of LoD-aware reuse (LOD paper 4.2: "an additional BVH in UV
// space for each LoD object as an auxiliary data structure for UV inversion"): for every instance
// with more than one LoD level (a LoD group), a plane z = 2 * plane holding each level's triangles
// at their UVs (u, v, z), under instance mask 1 << level, so that one ray query along z through
// (u, v) at a level's mask meets every triangle of that level whose UV triangle holds (u, v), with
// its barycentrics (shaders/include/scene_bridge.glsl, lod_points_at). One UV BLAS per LoD mesh
// (one geometry per primitive, as the render BLAS, so geometry and primitive indices agree), shared
// by the instances that use the mesh. Built once at scene upload; never updated (UVs do not move).
// Also the LoD table (GpuLodHeader, GpuLodInstance per instance) that the resolver reads.
#include <cstdint>
#include <memory>
#include <vector>

#include "gpu/accel.h"
#include "gpu/buffer.h"
#include "restir/lod_mapping.h"
#include "scene/scene.h"

namespace strata::render {

// Session options of LoD-aware reuse (lod_mapping, lod_matching, lod_vertices).
struct LodMappingSettings {
  bool uv = false;        // tau maps points across LoD switches (else they are refused as stale)
  bool matching = true;   // Alg. 1 settles UVs that several points share
  uint32_t vertices = gpu::LOD_VERTEX_PRIMARY | gpu::LOD_VERTEX_RECONNECTION;
};

class LodUvSpace {
 public:
  // Whether the scene has a LoD group (an instance with two or more levels).
  static bool needed(const scene::Scene& scene);
  // `mesh_primitive_base`: per mesh, its first GpuPrimitive in the scene's primitive records.
  LodUvSpace(const gpu::Context& ctx, const scene::Scene& scene, const std::vector<uint32_t>& mesh_primitive_base);

  const gpu::Tlas& tlas() const { return *tlas_; }
  const gpu::Buffer& table() const { return table_; }
  // Writes the session's options into the table's header (read by the next frame's passes).
  void set_settings(const LodMappingSettings& s);
  uint32_t planes() const { return planes_; }
  VkDeviceSize bytes() const;

 private:
  std::vector<gpu::Blas> blas_;   // per LoD mesh
  gpu::Buffer vertices_, indices_;
  std::unique_ptr<gpu::Tlas> tlas_;
  gpu::Buffer table_;             // GpuLodHeader, then GpuLodInstance per scene instance
  uint32_t instances_ = 0;
  uint32_t planes_ = 0;
};

}  // namespace strata::render
