#pragma once
// A scene on the device: geometry and materials uploaded once, one BLAS per mesh (every LoD level),
// and per frame the instance records, the TLAS (refit when only transforms move) and the emitter
// tables, all in render space (world space with the camera at the origin).
// With history (methods with temporal reuse), the instance records and the TLAS exist twice, in
// two slots used alternately, so that the previous frame's scene stays on the device, untouched,
// in the same command buffer as the current one (docs/ARCHITECTURE.md, State, session state).
#include <algorithm>
#include <memory>
#include <span>
#include <string>
#include <vector>

#include "gpu/accel.h"
#include "gpu/buffer.h"
#include "gpu/pipeline.h"
#include "include/bindings.h"
#include "include/frame_data.h"
#include "include/scene_data.h"
#include "render/emitters.h"
#include "render/lod_uv_space.h"
#include "render/scene_deform.h"
#include "render/scene_environment.h"
#include "render/scene_textures.h"
#include "scene/scene.h"

namespace strata::render {

struct SceneMemory {
  VkDeviceSize geometry = 0;       // vertices, indices, primitive and material records
  VkDeviceSize acceleration = 0;   // BLAS, TLAS, scratch
  VkDeviceSize per_frame = 0;      // instances, emitters, alias table, punctual lights, light tree
  VkDeviceSize history = 0;        // the previous frame's slot: second TLAS, its scratch, instances
  VkDeviceSize lod_uv = 0;         // LoD-aware reuse: UV BLASes, UV TLAS, LoD table (scenes with LoD groups, with history)
  VkDeviceSize textures = 0;       // texels, texture and level tables, material texture records, vertex extras (textured scenes)
  VkDeviceSize environment = 0;    // the environment map's radiance and sampling tables (scenes with a map)
  VkDeviceSize deformation = 0;    // deforming instances' vertex copies' BLASes, jobs, morph targets, skins, frame matrices (scenes with them)
};

class GpuScene {
 public:
  // Without `keep_history` there is one slot and nothing of the previous frame is kept on the device.
  // With `light_tree`, lights are chosen by the frame's light tree (render/light_tree.h), else by
  // power (the alias table).
  GpuScene(const gpu::Context& ctx, const scene::Scene& scene, bool keep_history = false, bool light_tree = false);

  // Uploads instance records and emitter tables for `frame` and records the TLAS build or refit.
  // With history, the frame goes to the slot the frame before last used (parity() flips), and the
  // very first frame is written to both slots so that the previous slot is always valid to bind.
  // Returns the render-space origin (the camera position) used.
  glm::dvec3 record_update(VkCommandBuffer cmd, const scene::FrameState& frame);
  // Records the deformation of the skinned and morphing instances into the slot(s) the next
  // record_update writes (render/scene_deform.h): the pass `deform` and their BLAS updates. A caller
  // that times it apart calls it first; else record_update does. Nothing for a scene without them.
  void record_deformation(VkCommandBuffer cmd, const scene::FrameState& frame);

  const scene::Scene& scene() const { return scene_; }
  // The descriptor bindings of the scene bridge (shaders/include/scene_bridge.glsl), plus the
  // emitter tables of light sampling when `with_lights`, plus BINDING_TLAS_PREV and
  // BINDING_INSTANCES_PREV when `with_history`, plus the textures of a textured scene; bind()
  // fills them in a set.
  std::vector<gpu::Binding> bindings(bool with_lights, bool with_history = false) const;
  // Textures and alpha-tested materials (render/scene_textures.h): a scene that has them runs the
  // textured variant of every pass that reads the scene (`shader(name)`: name + "_textured",
  // compiled with STRATA_TEXTURES), with SPEC_ALPHA_TEST on when some material is alpha-tested
  // (`add_spec`); any other scene runs the plain passes and binds none of it.
  bool textured() const { return textures_ != nullptr; }
  bool alpha_tested() const { return textures_ && textures_->any_alpha_tested(); }
  std::string shader(const char* name) const { return textured() ? std::string(name) + "_textured" : std::string(name); }
  void add_spec(std::vector<gpu::SpecConstant>& spec) const {
    if (alpha_tested()) spec.push_back({SPEC_ALPHA_TEST, VK_TRUE});
    if (has_environment_map()) spec.push_back({SPEC_ENV_MAP, VK_TRUE});
    if (light_tree_) spec.push_back({SPEC_LIGHT_TREE, VK_TRUE});
  }
  // Lights are chosen by the light tree: every pass compiles it in (SPEC_LIGHT_TREE) and reads the
  // tree of either frame by the device addresses in the frame constants (light_tree_address).
  bool light_tree() const { return light_tree_; }
  VkDeviceAddress light_tree_address(int slot) const { return light_tree_ ? slots_.at(size_t(slot)).light_tree.address() : 0; }
  // With the tree: some light of the last recorded frame differs from the frame before's (moved,
  // turned, changed power or level), so a light's probability at a point may differ between them.
  bool lights_changed() const { return lights_changed_; }
  // The scene's environment is a map (render/scene_environment.h): every pass compiles it in
  // (SPEC_ENV_MAP) and reads it by the device address in the frame constants.
  bool has_environment_map() const { return environment_ != nullptr; }
  VkDeviceAddress environment_map_address() const { return environment_ ? environment_->address() : 0; }
  // The map's weight against the light table (SceneEnvironment::power); 0 without a map.
  double environment_power() const { return environment_power_; }
  // The scene has KHR_lights_punctual lights: passes that sample lights compile them in
  // (SPEC_PUNCTUAL) and read their records by the device addresses in the frame constants
  // (lights(slot)); a scene without binds and compiles none of it.
  bool has_punctual() const { return !scene_.lights.empty(); }
  uint32_t light_count() const { return uint32_t(scene_.lights.size()); }
  // Device address of the punctual light records of the frame a slot holds (0 without lights).
  VkDeviceAddress lights_address(int slot) const { return has_punctual() ? slots_.at(size_t(slot)).lights.address() : 0; }
  // Some punctual light of the last recorded frame is not where the frame before had it.
  bool lights_moved() const { return lights_moved_; }
  // LoD-aware reuse (with history): the session's options, read by the next frame's passes. The
  // UV-space structure exists only for scenes with LoD groups (render/lod_uv_space.h).
  void set_lod_mapping(const LodMappingSettings& s);
  bool has_lod_groups() const { return lod_uv_ != nullptr; }
  // Passes with history compile the mapping in (SPEC_LOD_MAPPING): LoD groups and lod_mapping on.
  bool lod_mapping_compiled() const { return lod_uv_ != nullptr && lod_mapping_on_; }
  // Binds the current slot. With history that goes stale at the next update: use the overload below.
  void bind(gpu::DescriptorSet& set, bool with_lights) const;
  // Binds slot `parity` as the current frame and slot 1 - parity as the previous one: a method
  // builds one set per parity once and dispatches with the set of parity() each frame.
  void bind(gpu::DescriptorSet& set, bool with_lights, bool with_history, int parity) const;

  bool keeps_history() const { return slots_.size() == 2; }
  int parity() const { return parity_; }  // slot of the last recorded frame (always 0 without history)
  // Slot 1 - parity() holds the frame before the last one (false after the first frame: it holds
  // a copy of that frame then).
  bool history_valid() const { return keeps_history() && frames_ >= 2; }
  // Some transform or LoD level or punctual light of the last recorded frame differs from the frame before it.
  bool moved_since_previous() const { return changed_instances() != 0 || lights_moved_; }
  // Per instance, what changed between the frame before and the last recorded one
  // (INSTANCE_CHANGED_*; the same bits are in the device's instance records of that frame).
  const std::vector<uint32_t>& instance_changes() const { return changes_; }
  // How many instances changed. With history, their swept boxes (GpuSweptBoxes) are bound as BINDING_SWEPT_BOXES; more than
  // SWEPT_BOXES_MAX changed instances are too many to list (every ray then counts as meeting one).
  uint32_t changed_instances() const {
    return uint32_t(std::count_if(changes_.begin(), changes_.end(), [](uint32_t c) { return c != 0; }));
  }
  // The frame state recorded before the last one (the last one itself after the first update).
  const scene::FrameState& previous_frame() const { return previous_; }

  const gpu::Buffer& vertices() const { return vertices_; }
  const gpu::Buffer& indices() const { return indices_; }
  const gpu::Buffer& primitives() const { return primitives_; }
  const gpu::Buffer& materials() const { return materials_; }
  const gpu::Buffer& instances() const { return slots_[size_t(parity_)].instances; }
  const gpu::Buffer& instances(int slot) const { return slots_.at(size_t(slot)).instances; }
  const gpu::Buffer& emitters() const { return emitters_; }
  const gpu::Buffer& alias() const { return alias_; }
  const gpu::Tlas& tlas() const { return *slots_[size_t(parity_)].tlas; }
  const gpu::Tlas& tlas(int slot) const { return *slots_.at(size_t(slot)).tlas; }
  // Render-space origin (world position of the camera) of the frame a slot holds.
  glm::dvec3 origin(int slot) const { return slots_.at(size_t(slot)).origin; }
  // TLAS builds and refits over both slots, one per recorded frame (the seed of the first frame's
  // previous slot is not counted): what FrameStats::tlas_builds/refits report.
  uint32_t tlas_builds() const;
  uint32_t tlas_refits() const;
  uint32_t emitter_count() const { return emitter_count_; }
  double total_emitter_power() const { return total_power_; }
  // Light-selection totals of the previous frame (those of the last one after the first update).
  uint32_t prev_emitter_count() const { return prev_emitter_count_; }
  double prev_total_emitter_power() const { return prev_total_power_; }
  // The emitter table of the last recorded frame chooses other lights from the same random numbers
  // than the frame before's (an emitter's power, LoD level or the set of emitters changed). With
  // the light tree, whose choice each frame makes from its own tree: the table lists other lights
  // (another set of emitters, or in another order).
  bool lights_reselected() const { return lights_reselected_; }
  bool has_emitters() const { return has_emitters_; }
  // Skinned or morphing instances (render/scene_deform.h); null for a scene without.
  const SceneDeformation* deformation() const { return deformation_.get(); }
  SceneMemory memory() const;
  uint64_t max_triangles_per_frame() const;

 private:
  // One frame's scene on the device: its instance records and TLAS.
  struct Slot {
    std::unique_ptr<gpu::Tlas> tlas;
    gpu::Buffer instances;
    gpu::Buffer lights;               // the frame's GpuPunctualLight records (scenes with punctual lights)
    gpu::Buffer light_tree;           // the frame's light tree (light_sampler tree)
    std::vector<uint32_t> last_lods;  // of this TLAS's last build: a refit needs the same BLASes
    glm::dvec3 origin{0.0};
  };
  void upload_geometry(uint32_t slot_count, const std::vector<uint32_t>& copies);
  // World-space bounds of instance i in `frame`; the swept boxes of the changed ones, uploaded.
  std::pair<glm::dvec3, glm::dvec3> world_bounds(const scene::FrameState& frame, size_t i) const;
  void upload_swept_boxes(const scene::FrameState& frame, glm::dvec3 origin);
  void record_light_tree(const EmitterTable& table);
  void write_slot(VkCommandBuffer cmd, Slot& slot, const scene::FrameState& frame, glm::dvec3 origin,
                  std::span<const gpu::GpuInstance> records, std::span<const VkAccelerationStructureInstanceKHR> tlas_instances);
  const gpu::Context& ctx_;
  const scene::Scene& scene_;
  gpu::Buffer vertices_, indices_, primitives_, materials_;
  gpu::Buffer emitters_, alias_;
  std::vector<gpu::Blas> blas_;                 // per mesh
  std::vector<uint32_t> mesh_primitive_base_;   // per mesh: first GpuPrimitive
  std::vector<std::pair<glm::vec3, glm::vec3>> mesh_bounds_;  // per mesh: object-space lower and upper corner
  gpu::Buffer swept_;                           // GpuSweptBoxes (with history)
  std::unique_ptr<LodUvSpace> lod_uv_;          // with history, for scenes with LoD groups
  std::unique_ptr<SceneTextures> textures_;     // scenes with textures or alpha-tested materials
  std::unique_ptr<SceneEnvironment> environment_;  // scenes with an environment map
  std::unique_ptr<SceneDeformation> deformation_;  // scenes with skinned or morphing instances
  bool deformed_ = false;                       // record_deformation ran for the next record_update
  double environment_power_ = 0.0;
  gpu::Buffer lod_off_table_;                   // with history, without LoD groups: a header that says "off"
  bool lod_mapping_on_ = false;
  std::vector<Slot> slots_;                     // 1, or 2 with history
  int parity_ = 0;
  uint32_t frames_ = 0;                         // record_update calls so far
  uint32_t seed_builds_ = 0;                    // TLAS builds that seeded the previous slot
  scene::FrameState current_, previous_;
  std::vector<uint32_t> changes_;               // per instance, INSTANCE_CHANGED_* of the last frame
  std::vector<bool> instance_emits_;            // per instance: some level has emissive triangles
  bool has_emitters_ = false;
  double scene_radius_ = 1.0;                   // scene_bounding_radius (directional lights' and the environment map's power)
  bool lights_moved_ = false;
  uint32_t emitter_count_ = 0;
  uint32_t emitter_capacity_ = 0;
  double total_power_ = 0.0;
  uint32_t prev_emitter_count_ = 0;
  double prev_total_power_ = 0.0;
  struct LightSelection {
    std::vector<uint32_t> choices;      // per emitter its surface, per alias column its alias
    std::vector<float> probabilities;   // per emitter its pmf, per alias column its threshold
    bool same_as(const LightSelection& o) const;
  };
  LightSelection light_selection_;  // of the last recorded frame's emitter table
  bool lights_reselected_ = false;
  bool light_tree_ = false;
  bool lights_changed_ = false;
  std::vector<uint32_t> light_entries_;  // of the last recorded frame's table: per entry its instance, geometry, triangle
};

}  // namespace strata::render
