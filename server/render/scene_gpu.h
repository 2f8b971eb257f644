#pragma once
// A scene on the device: geometry and materials uploaded once, one BLAS per mesh (every LoD level),
// and per frame the instance records, the TLAS (refit when only transforms move) and the emitter
// tables, all in render space (world space with the camera at the origin).
#include <memory>
#include <vector>

#include "gpu/accel.h"
#include "gpu/buffer.h"
#include "gpu/pipeline.h"
#include "include/frame_data.h"
#include "include/scene_data.h"
#include "render/emitters.h"
#include "scene/scene.h"

namespace strata::render {

struct SceneMemory {
  VkDeviceSize geometry = 0;       // vertices, indices, primitive and material records
  VkDeviceSize acceleration = 0;   // BLAS, TLAS, scratch
  VkDeviceSize per_frame = 0;      // instances, emitters, alias table
};

class GpuScene {
 public:
  GpuScene(const gpu::Context& ctx, const scene::Scene& scene);

  // Uploads instance records and emitter tables for `frame` and records the TLAS build or refit.
  // Returns the render-space origin (the camera position) used.
  glm::dvec3 record_update(VkCommandBuffer cmd, const scene::FrameState& frame);

  const scene::Scene& scene() const { return scene_; }
  // The descriptor bindings of the scene bridge (shaders/include/scene_bridge.glsl), plus the
  // emitter tables of light sampling when `with_lights`; bind() fills them in a set.
  static std::vector<gpu::Binding> bindings(bool with_lights);
  void bind(gpu::DescriptorSet& set, bool with_lights) const;

  const gpu::Buffer& vertices() const { return vertices_; }
  const gpu::Buffer& indices() const { return indices_; }
  const gpu::Buffer& primitives() const { return primitives_; }
  const gpu::Buffer& materials() const { return materials_; }
  const gpu::Buffer& instances() const { return instances_; }
  const gpu::Buffer& emitters() const { return emitters_; }
  const gpu::Buffer& alias() const { return alias_; }
  const gpu::Tlas& tlas() const { return *tlas_; }
  uint32_t emitter_count() const { return emitter_count_; }
  double total_emitter_power() const { return total_power_; }
  bool has_emitters() const { return has_emitters_; }
  SceneMemory memory() const;
  uint64_t max_triangles_per_frame() const;

 private:
  void upload_geometry();
  const gpu::Context& ctx_;
  const scene::Scene& scene_;
  gpu::Buffer vertices_, indices_, primitives_, materials_;
  gpu::Buffer instances_, emitters_, alias_;
  std::vector<gpu::Blas> blas_;                 // per mesh
  std::vector<uint32_t> mesh_primitive_base_;   // per mesh: first GpuPrimitive
  std::unique_ptr<gpu::Tlas> tlas_;
  std::vector<uint32_t> last_lods_;
  bool has_emitters_ = false;
  uint32_t emitter_count_ = 0;
  uint32_t emitter_capacity_ = 0;
  double total_power_ = 0.0;
};

}  // namespace strata::render
