#pragma once
// Deforming meshes on the device (glTF skins and morph targets; docs/ARCHITECTURE.md, "Deforming
// meshes"). Every deforming instance gets, per scene slot (one, or two with history), its own copy
// of its mesh's vertices, primitive records pointing at that copy, and a BLAS over it. Each frame
// the pass `deform` (shaders/passes/deform.comp) writes the slot's copies from the rest vertices,
// the morph targets and the frame's skinning matrices and weights, then each copy's BLAS is refit
// (or rebuilt, below) before the slot's TLAS is built. The slot's instance records point at the
// slot's copies, so the previous slot keeps the previous frame's deformed surfaces: the surface
// resolver maps a stored hit (instance, triangle, barycentrics) to the same barycentrics of the same
// triangle in either frame, as for a rigid instance. A scene without deforming instances has none of it.
#include <array>
#include <memory>
#include <span>
#include <string>
#include <vector>

#include <glm/glm.hpp>

#include "gpu/accel.h"
#include "gpu/buffer.h"
#include "include/deform_data.h"
#include "include/scene_data.h"
#include "scene/deform.h"
#include "scene/scene.h"

namespace strata::render {

class Pass;

class SceneDeformation {
 public:
  static bool needed(const scene::Scene& scene);
  // The meshes whose vertices follow the rest vertices in the vertex buffer, in order: per deforming
  // instance (in instance order) and per slot, its mesh. GpuScene::upload_geometry appends them, and
  // the vertex extras of textured scenes follow the same order (render/scene_textures.h).
  static std::vector<uint32_t> copied_meshes(const scene::Scene& scene, uint32_t slots);

  // `copy_vertex_base[c]` and `copy_primitive_base[c]`: where copy c of copied_meshes() starts in the
  // vertex buffer and the primitive records; `mesh_vertex_base`: per mesh, where its rest vertices start.
  struct Layout {
    std::vector<uint32_t> copy_vertex_base;
    std::vector<uint32_t> copy_primitive_base;
    std::vector<uint32_t> mesh_vertex_base;
    std::vector<std::vector<gpu::BlasTriangles>> copy_geometries;  // per copy, its BLAS's geometries
  };
  SceneDeformation(const gpu::Context& ctx, const scene::Scene& scene, uint32_t slots, const Layout& layout,
                   const gpu::Buffer& vertices);
  ~SceneDeformation();
  SceneDeformation(const SceneDeformation&) = delete;
  SceneDeformation& operator=(const SceneDeformation&) = delete;

  bool deforms(size_t instance) const { return copy_of_[instance] >= 0; }
  // Where instance i's primitives and BLAS are in slot s (deforming instances only).
  uint32_t primitive_base(size_t instance, int slot) const;
  uint32_t vertex_base(size_t instance, int slot) const;  // its copy's first vertex (its primitives' in order)
  VkDeviceAddress blas_address(size_t instance, int slot) const;

  // Records the deformation of every deforming instance of `frame` into slot `slot`: the frame's
  // skinning matrices and morph weights uploaded, the pass, a barrier, and each copy's BLAS refit or
  // rebuilt; the caller then builds the slot's TLAS.
  void record(VkCommandBuffer cmd, int slot, const scene::FrameState& frame);

  // A box holding instance i's deformed vertices at `frame`, in its object space: per joint the box
  // of the rest vertices it moves, grown by the most the morph targets can displace them at the
  // frame's weights, through S_j; the union over joints (the rest box, grown, when not skinned).
  std::pair<glm::vec3, glm::vec3> object_bounds(size_t instance, const scene::FrameState& frame) const;

  // BLAS updates over every recorded frame: refits, and rebuilds (a copy is rebuilt instead of
  // refit when its box's surface area has grown past k_rebuild_growth times the area at its last
  // build: a refit keeps the tree of the build, whose boxes then overlap more and more).
  uint32_t refits() const;
  uint32_t rebuilds() const;
  uint32_t deformed_vertices() const { return vertices_per_slot_; }
  uint64_t bytes() const;
  static constexpr double k_rebuild_growth = 1.5;

 private:
  // object_bounds at the frame's morph weights `w` and skinning matrices `s` (scene/deform.h).
  std::pair<glm::vec3, glm::vec3> bounds(size_t instance, std::span<const float> w, std::span<const scene::SkinningMatrix> s) const;

  struct Instance {
    std::vector<std::pair<glm::vec3, glm::vec3>> joint_boxes;  // per joint (skinned), or one rest box
    std::vector<glm::vec3> target_reach;                       // per target: the largest |delta| per axis
    uint32_t joint_offset = 0;                                 // into the frame's skinning matrices
    uint32_t weight_offset = 0;                                // into the frame's morph weights
  };
  const scene::Scene& scene_;
  std::vector<int> copy_of_;  // per instance: index of its first copy (slot 0), or -1
  std::vector<Instance> instances_;  // per deforming instance
  std::vector<uint32_t> primitive_base_;  // per copy
  std::vector<uint32_t> vertex_base_;     // per copy
  std::vector<gpu::DeformingBlas> blas_;  // per copy
  std::vector<double> built_area_;        // per copy: its box's surface area at its last build
  uint32_t slots_;
  uint32_t vertices_per_slot_ = 0;
  uint32_t joint_count_ = 0;
  uint32_t weight_count_ = 0;
  std::array<gpu::Buffer, 2> jobs_;       // per slot (slot 1 = slot 0 without history)
  gpu::Buffer vertex_job_, morph_deltas_, skin_vertices_;
  std::array<gpu::Buffer, 2> matrices_, weights_;  // per slot: the frame's skinning matrices and morph weights
  std::unique_ptr<Pass> pass_;
};

}  // namespace strata::render
