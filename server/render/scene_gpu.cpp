#include "render/scene_gpu.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>
#include <glm/gtc/type_ptr.hpp>

#include "include/bindings.h"
#include "render/light_tree.h"
#include "render/punctual_lights.h"

namespace strata::render {
namespace {

constexpr VkBufferUsageFlags k_geometry_usage =
    gpu::k_storage_usage | VK_BUFFER_USAGE_ACCELERATION_STRUCTURE_BUILD_INPUT_READ_ONLY_BIT_KHR;

}  // namespace

GpuScene::GpuScene(const gpu::Context& ctx, const scene::Scene& scene, bool keep_history, bool light_tree)
    : ctx_(ctx), scene_(scene), light_tree_(light_tree) {
  scene.validate();
  const uint32_t slot_count = keep_history ? 2 : 1;
  const std::vector<uint32_t> copies =
      SceneDeformation::needed(scene) ? SceneDeformation::copied_meshes(scene, slot_count) : std::vector<uint32_t>{};
  if (SceneTextures::needed(scene)) textures_ = std::make_unique<SceneTextures>(ctx, scene, copies);
  upload_geometry(slot_count, copies);
  slots_.resize(slot_count);
  for (auto& slot : slots_) {
    slot.tlas = std::make_unique<gpu::Tlas>(ctx, uint32_t(scene.instances.size()));
    slot.instances = gpu::Buffer(ctx, std::max<size_t>(16, sizeof(gpu::GpuInstance) * scene.instances.size()),
                                 gpu::k_storage_usage, gpu::Memory::Host, "instances");
    if (has_punctual())
      slot.lights = gpu::Buffer(ctx, sizeof(gpu::GpuPunctualLight) * scene.lights.size(), gpu::k_storage_usage,
                                gpu::Memory::Host, "punctual lights");
  }
  if (has_punctual() || SceneEnvironment::needed(scene.environment)) scene_radius_ = scene_bounding_radius(scene);
  if (SceneEnvironment::needed(scene.environment)) {
    environment_ = std::make_unique<SceneEnvironment>(ctx, *scene.environment.map);
    environment_power_ = SceneEnvironment::power(*scene.environment.map, scene_radius_);
  }
  if (keep_history) {
    swept_ = gpu::Buffer(ctx, sizeof(gpu::GpuSweptBoxes), gpu::k_storage_usage, gpu::Memory::Host, "swept boxes");
    if (LodUvSpace::needed(scene)) {
      lod_uv_ = std::make_unique<LodUvSpace>(ctx, scene, mesh_primitive_base_);
    } else {
      lod_off_table_ = gpu::Buffer(ctx, sizeof(gpu::GpuLodHeader) + sizeof(gpu::GpuLodInstance), gpu::k_storage_usage,
                                   gpu::Memory::Host, "lod table");
      const gpu::GpuLodHeader off{gpu::LOD_MODE_OFF, 0u, 0u, 0u};
      lod_off_table_.upload(&off, sizeof off);
    }
  }
  // Emitter capacity: the most emissive triangles any LoD choice can produce.
  size_t capacity = 0;
  for (const auto& inst : scene.instances) {
    size_t most = 0;
    instance_emits_.push_back(false);
    for (uint32_t mesh : inst.lod_meshes) {
      size_t n = 0;
      for (const auto& p : scene.meshes[mesh].primitives)
        if (glm::any(glm::greaterThan(scene.materials[p.material].emission, glm::vec3(0.0f)))) n += p.triangle_count();
      most = std::max(most, n);
      if (n > 0) instance_emits_.back() = true;
    }
    capacity += most;
  }
  has_emitters_ = capacity > 0;
  emitter_capacity_ = uint32_t(capacity);
  emitters_ = gpu::Buffer(ctx, std::max<size_t>(16, sizeof(gpu::GpuEmitter) * capacity), gpu::k_storage_usage, gpu::Memory::Host,
                          "emitters");
  alias_ = gpu::Buffer(ctx, std::max<size_t>(16, sizeof(gpu::GpuAliasEntry) * (capacity + scene.lights.size())),
                       gpu::k_storage_usage, gpu::Memory::Host,
                       "emitter alias table");
  if (light_tree_) {
    // The largest tree any LoD choice gives (LightTree::bytes): header, at most 2n - 1 nodes and n
    // trails over n entries, the directional lights, per instance a record, per geometry of an
    // emitting instance a record, per emitter its triangle; each array padded to 16 bytes.
    const size_t entries = capacity + scene.lights.size();
    size_t geometries = 0;
    for (const auto& inst : scene.instances) {
      size_t most = 0;
      for (uint32_t mesh : inst.lod_meshes) most = std::max(most, scene.meshes[mesh].primitives.size());
      geometries += most;
    }
    const size_t bytes = sizeof(gpu::GpuLightTreeHeader) + 2 * entries * sizeof(gpu::GpuLightNode) + entries * 16 +
                         scene.lights.size() * 8 + scene.instances.size() * 8 + geometries * 8 + capacity * 4 + 7 * 16;
    for (auto& slot : slots_)
      slot.light_tree = gpu::Buffer(ctx, bytes, gpu::k_storage_usage, gpu::Memory::Host, "light tree");
  }
}

void GpuScene::upload_geometry(uint32_t slot_count, const std::vector<uint32_t>& copies) {
  std::vector<gpu::GpuVertex> vertices;
  std::vector<uint32_t> indices;
  std::vector<gpu::GpuPrimitive> prims;
  struct Range {
    uint32_t vertex_offset, vertex_count, index_offset, triangle_count;
    bool opaque;
  };
  std::vector<std::vector<Range>> ranges(scene_.meshes.size());
  SceneDeformation::Layout layout;
  for (size_t m = 0; m < scene_.meshes.size(); ++m) {
    mesh_primitive_base_.push_back(uint32_t(prims.size()));
    layout.mesh_vertex_base.push_back(uint32_t(vertices.size()));
    glm::vec3 lo(std::numeric_limits<float>::max());
    glm::vec3 hi(-std::numeric_limits<float>::max());
    for (const auto& p : scene_.meshes[m].primitives) {
      for (const auto& x : p.positions) {
        lo = glm::min(lo, x);
        hi = glm::max(hi, x);
      }
      Range r{uint32_t(vertices.size()), uint32_t(p.positions.size()), uint32_t(indices.size()), uint32_t(p.triangle_count()), true};
      r.opaque = !SceneTextures::alpha_tested(scene_.materials[p.material]);
      for (size_t v = 0; v < p.positions.size(); ++v)
        vertices.push_back({glm::vec4(p.positions[v], p.uvs[v].x), glm::vec4(p.normals[v], p.uvs[v].y)});
      indices.insert(indices.end(), p.indices.begin(), p.indices.end());
      prims.push_back({r.vertex_offset, r.index_offset, r.triangle_count, p.material});
      ranges[m].push_back(r);
    }
    mesh_bounds_.push_back({lo, hi});
  }
  // The deforming instances' copies (render/scene_deform.h): the rest vertices again, which the
  // deformation pass overwrites every frame, with primitive records of their own.
  std::vector<std::vector<Range>> copy_ranges;
  for (uint32_t m : copies) {
    layout.copy_vertex_base.push_back(uint32_t(vertices.size()));
    layout.copy_primitive_base.push_back(uint32_t(prims.size()));
    const uint32_t first = layout.mesh_vertex_base[m];
    copy_ranges.emplace_back();
    uint32_t offset = 0;
    for (const Range& rest : ranges[m]) {
      Range r = rest;
      r.vertex_offset = uint32_t(vertices.size());
      vertices.insert(vertices.end(), vertices.begin() + first + offset, vertices.begin() + first + offset + rest.vertex_count);
      offset += rest.vertex_count;
      const gpu::GpuPrimitive& rp = prims[mesh_primitive_base_[m] + copy_ranges.back().size()];
      prims.push_back({r.vertex_offset, rp.index_offset, rp.triangle_count, rp.material});
      copy_ranges.back().push_back(r);
    }
  }
  std::vector<gpu::GpuMaterial> mats;
  for (const auto& m : scene_.materials) {
    mats.push_back({glm::vec4(m.base_color, m.metallic), glm::vec4(m.emission, m.roughness), m.specular,
                    m.double_sided ? gpu::MATERIAL_DOUBLE_SIDED : 0u, 0, 0});
  }
  vertices_ = gpu::make_buffer<gpu::GpuVertex>(ctx_, vertices, k_geometry_usage, gpu::Memory::Device, "vertices");
  indices_ = gpu::make_buffer<uint32_t>(ctx_, indices, k_geometry_usage, gpu::Memory::Device, "indices");
  primitives_ = gpu::make_buffer<gpu::GpuPrimitive>(ctx_, prims, gpu::k_storage_usage, gpu::Memory::Device, "primitives");
  materials_ = gpu::make_buffer<gpu::GpuMaterial>(ctx_, mats, gpu::k_storage_usage, gpu::Memory::Device, "materials");

  auto geometries = [&](const std::vector<Range>& rs) {
    std::vector<gpu::BlasTriangles> geoms;
    for (const auto& r : rs) {
      geoms.push_back({vertices_.address() + VkDeviceAddress(r.vertex_offset) * sizeof(gpu::GpuVertex), r.vertex_count,
                       uint32_t(sizeof(gpu::GpuVertex)), indices_.address() + VkDeviceAddress(r.index_offset) * sizeof(uint32_t),
                       r.triangle_count, r.opaque});
    }
    return geoms;
  };
  for (size_t m = 0; m < scene_.meshes.size(); ++m) blas_.emplace_back(ctx_, geometries(ranges[m]));
  if (!copies.empty()) {
    for (const auto& rs : copy_ranges) layout.copy_geometries.push_back(geometries(rs));
    deformation_ = std::make_unique<SceneDeformation>(ctx_, scene_, slot_count, layout, vertices_);
  }
}

void GpuScene::record_deformation(VkCommandBuffer cmd, const scene::FrameState& frame) {
  if (!deformation_) return;
  const int slot = keeps_history() && frames_ > 0 ? 1 - parity_ : parity_;  // the slot record_update writes next
  deformation_->record(cmd, slot, frame);
  if (keeps_history() && frames_ == 0) deformation_->record(cmd, 1 - slot, frame);  // the seeded slot
  deformed_ = true;
}

glm::dvec3 GpuScene::record_update(VkCommandBuffer cmd, const scene::FrameState& frame) {
  if (deformation_ && !deformed_) record_deformation(cmd, frame);
  deformed_ = false;
  // With history the previous frame's slot stays untouched: temporal passes of this frame read it.
  if (keeps_history() && frames_ > 0) parity_ = 1 - parity_;
  glm::dvec3 origin(frame.camera.position);
  std::vector<gpu::GpuInstance> records;
  std::vector<VkAccelerationStructureInstanceKHR> tlas_instances;
  changes_.assign(scene_.instances.size(), 0u);
  std::vector<size_t> deforming;  // instances whose records and TLAS entries differ by slot
  for (size_t i = 0; i < scene_.instances.size(); ++i) {
    uint32_t mesh = scene_.instances[i].lod_meshes[frame.lods[i]];
    glm::mat4 m = object_to_render(frame.transforms[i], origin);
    glm::mat3 upper(m);
    bool mirrored = glm::determinant(upper) < 0.0f;
    glm::mat4 normal_matrix(glm::transpose(glm::inverse(upper)));
    uint32_t changes = 0;
    if (frames_ > 0) {
      if (frame.transforms[i] != current_.transforms[i]) changes |= gpu::INSTANCE_CHANGED_TRANSFORM;
      if (frame.lods[i] != current_.lods[i]) changes |= gpu::INSTANCE_CHANGED_LOD;
      if (deformation_ && deformation_->deforms(i) &&
          (!std::ranges::equal(scene::joints_at(scene_, frame, i), scene::joints_at(scene_, current_, i)) ||
           !std::ranges::equal(scene::morph_weights_at(scene_, frame, i), scene::morph_weights_at(scene_, current_, i))))
        changes |= gpu::INSTANCE_CHANGED_SHAPE;
      if (changes && instance_emits_[i]) changes |= gpu::INSTANCE_CHANGED_EMISSION;
    }
    changes_[i] = changes;
    records.push_back({m, normal_matrix, mesh_primitive_base_[mesh], frame.lods[i], mesh,
                       (mirrored ? gpu::INSTANCE_FLAG_MIRRORED : 0u) | changes});
    VkAccelerationStructureInstanceKHR vi{};
    vi.transform = gpu::to_vk_transform(glm::value_ptr(m));
    vi.instanceCustomIndex = uint32_t(i) & 0xFFFFFFu;  // 24 bits; LoadLimits keeps instances far below
    vi.mask = 0xFF;
    vi.flags = VK_GEOMETRY_INSTANCE_TRIANGLE_FACING_CULL_DISABLE_BIT_KHR;
    vi.accelerationStructureReference = blas_[mesh].address();
    tlas_instances.push_back(vi);
    if (deformation_ && deformation_->deforms(i)) deforming.push_back(i);
  }
  // A deforming instance's record and TLAS entry name the slot's own vertex copy and its BLAS, which
  // record_deformation wrote first (render/scene_deform.h).
  auto write = [&](int slot) {
    if (deformation_) {
      for (size_t i : deforming) {
        records[i].primitive_base = deformation_->primitive_base(i, slot);
        tlas_instances[i].accelerationStructureReference = deformation_->blas_address(i, slot);
      }
    }
    write_slot(cmd, slots_[size_t(slot)], frame, origin, records, tlas_instances);
  };
  write(parity_);
  if (keeps_history() && frames_ == 0) {
    // The first frame has no predecessor: it seeds the other slot too, so that descriptor sets
    // always bind built objects (history_valid() stays false until the second frame).
    write(1 - parity_);
    ++seed_builds_;
  }
  if (keeps_history()) upload_swept_boxes(frame, origin);
  lights_moved_ = frames_ > 0 && frame.lights != current_.lights;
  if (frames_ > 0) previous_ = std::move(current_);
  else previous_ = frame;
  current_ = frame;

  EmitterTable table = build_emitter_table(scene_, frame, origin, scene_radius_);
  if (has_punctual()) {
    // With history the other slot keeps the previous frame's records (its render space), as it keeps its instances.
    slots_[size_t(parity_)].lights.upload(table.lights.data(), table.lights.size() * sizeof(gpu::GpuPunctualLight));
    if (keeps_history() && frames_ == 0)
      slots_[size_t(1 - parity_)].lights.upload(table.lights.data(), table.lights.size() * sizeof(gpu::GpuPunctualLight));
  }
  prev_emitter_count_ = frames_ > 0 ? emitter_count_ : uint32_t(table.emitters.size());
  prev_total_power_ = frames_ > 0 ? total_power_ : table.total_power;
  emitter_count_ = uint32_t(table.emitters.size());
  total_power_ = table.total_power;
  if (light_tree_) {
    record_light_tree(table);
  } else {
    // Light selection: which emitter triangle each column of the alias table picks, and with which
    // probability. Where it differs, the same random numbers choose other lights in the two frames.
    // Probabilities are compared to 1e-5: a turning emitter's float area wobbles in the last bits,
    // which moves the alias thresholds by as much (a choice changes for a 1e-5 share of the numbers).
    LightSelection selection;
    for (const auto& e : table.emitters) {
      selection.probabilities.push_back(e.p1_pmf.w);
      for (int k = 0; k < 4; ++k) selection.choices.push_back(e.surface[k]);
    }
    for (const auto& l : table.lights) selection.probabilities.push_back(l.intensity_pmf.w);
    for (const auto& a : table.alias) {
      selection.probabilities.push_back(a.threshold);
      selection.choices.push_back(a.alias);
    }
    lights_reselected_ = frames_ > 0 && !selection.same_as(light_selection_);
    light_selection_ = std::move(selection);
  }
  ++frames_;
  if (emitter_count_ > emitter_capacity_) throw gpu::GpuError("emitter table overflow");
  emitters_.upload(table.emitters.data(), table.emitters.size() * sizeof(gpu::GpuEmitter));
  alias_.upload(table.alias.data(), table.alias.size() * sizeof(gpu::GpuAliasEntry));
  return origin;
}

std::pair<glm::dvec3, glm::dvec3> GpuScene::world_bounds(const scene::FrameState& frame, size_t i) const {
  const auto [lo, hi] = deformation_ && deformation_->deforms(i) ? deformation_->object_bounds(i, frame)
                                                                  : mesh_bounds_[scene_.instances[i].lod_meshes[frame.lods[i]]];
  const glm::dmat4 m(frame.transforms[i]);
  glm::dvec3 wlo(std::numeric_limits<double>::max());
  glm::dvec3 whi(-std::numeric_limits<double>::max());
  for (int c = 0; c < 8; ++c) {
    const glm::dvec3 corner((c & 1) ? hi.x : lo.x, (c & 2) ? hi.y : lo.y, (c & 4) ? hi.z : lo.z);
    const glm::dvec3 w(m * glm::dvec4(corner, 1.0));
    wlo = glm::min(wlo, w);
    whi = glm::max(whi, w);
  }
  return {wlo, whi};
}

// Called after changes_ holds this frame's changes and before current_ becomes the previous frame.
void GpuScene::upload_swept_boxes(const scene::FrameState& frame, glm::dvec3 origin) {
  gpu::GpuSweptBoxes boxes{};
  // The other slot holds the previous frame (the first frame seeds it with its own origin: zero).
  boxes.prev_to_current = glm::vec4(glm::vec3(slots_[size_t(1 - parity_)].origin - origin), 0.0f);
  uint32_t n = 0;
  for (size_t i = 0; i < changes_.size(); ++i) {
    if (changes_[i] == 0) continue;
    if (n < gpu::SWEPT_BOXES_MAX) {
      auto [lo, hi] = world_bounds(frame, i);
      const auto [plo, phi] = world_bounds(current_, i);  // the previous frame (current_ until the caller moves it)
      lo = glm::min(lo, plo) - origin;
      hi = glm::max(hi, phi) - origin;
      // Padded for the float rounding of render-space positions and of prev_to_current.
      const double pad = 1e-4 * (glm::length(hi - lo) + glm::length(hi + lo)) + 1e-6;
      boxes.lo[n] = glm::vec4(glm::vec3(lo - pad), 0.0f);
      boxes.hi[n] = glm::vec4(glm::vec3(hi + pad), 0.0f);
    }
    ++n;
  }
  boxes.count = n;
  swept_.upload(&boxes, sizeof boxes);
}

// The frame's light tree to the slot record_update writes (and, on the first frame with history,
// to the other slot too, as its punctual lights). Which lights the table lists decides whether the
// same random numbers still choose the same light in both frames' trees (lights_reselected); any
// light that moved, turned or changed level makes its probabilities differ (lights_changed).
void GpuScene::record_light_tree(const EmitterTable& table) {
  const LightTree tree = build_light_tree(table, scene_.lights, uint32_t(scene_.instances.size()));
  const std::vector<std::byte> bytes = tree.bytes();
  if (bytes.size() > slots_[size_t(parity_)].light_tree.size()) throw gpu::GpuError("light tree overflow");
  slots_[size_t(parity_)].light_tree.upload(bytes.data(), bytes.size());
  if (keeps_history() && frames_ == 0) slots_[size_t(1 - parity_)].light_tree.upload(bytes.data(), bytes.size());
  std::vector<uint32_t> entries;
  for (const auto& e : table.emitters) entries.insert(entries.end(), {e.surface.x, e.surface.y, e.surface.z});
  const bool relisted = frames_ > 0 && entries != light_entries_;
  light_entries_ = std::move(entries);
  const bool emitter_changed =
      std::ranges::any_of(changes_, [](uint32_t c) { return (c & gpu::INSTANCE_CHANGED_EMISSION) != 0u; });
  lights_reselected_ = relisted;
  lights_changed_ = frames_ > 0 && (relisted || lights_moved_ || emitter_changed);
}

bool GpuScene::LightSelection::same_as(const LightSelection& o) const {
  if (choices != o.choices || probabilities.size() != o.probabilities.size()) return false;
  for (size_t i = 0; i < probabilities.size(); ++i)
    if (std::abs(probabilities[i] - o.probabilities[i]) > 1e-5f * std::max(1.0f, std::abs(o.probabilities[i]))) return false;
  return true;
}

void GpuScene::write_slot(VkCommandBuffer cmd, Slot& slot, const scene::FrameState& frame, glm::dvec3 origin,
                          std::span<const gpu::GpuInstance> records,
                          std::span<const VkAccelerationStructureInstanceKHR> tlas_instances) {
  slot.instances.upload(records.data(), records.size_bytes());
  // Refit keeps the tree topology: valid while the same BLASes are referenced (no LoD switch since
  // this TLAS's own last build, which with history is the frame before last).
  slot.tlas->record_build(cmd, tlas_instances, frame.lods == slot.last_lods);
  slot.last_lods = frame.lods;
  slot.origin = origin;
}

uint32_t GpuScene::tlas_builds() const {
  uint32_t n = 0;
  for (const auto& slot : slots_) n += slot.tlas->builds();
  return n - seed_builds_;
}

uint32_t GpuScene::tlas_refits() const {
  uint32_t n = 0;
  for (const auto& slot : slots_) n += slot.tlas->refits();
  return n;
}

std::vector<gpu::Binding> GpuScene::bindings(bool with_lights, bool with_history) const {
  std::vector<gpu::Binding> b = {
      {BINDING_TLAS, VK_DESCRIPTOR_TYPE_ACCELERATION_STRUCTURE_KHR},
      {BINDING_VERTICES, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER},
      {BINDING_INDICES, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER},
      {BINDING_PRIMITIVES, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER},
      {BINDING_INSTANCES, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER},
      {BINDING_MATERIALS, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER},
  };
  if (with_lights) {
    b.push_back({BINDING_EMITTERS, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER});
    b.push_back({BINDING_ALIAS, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER});
  }
  if (with_history) {
    b.push_back({BINDING_TLAS_PREV, VK_DESCRIPTOR_TYPE_ACCELERATION_STRUCTURE_KHR});
    b.push_back({BINDING_INSTANCES_PREV, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER});
    b.push_back({BINDING_SWEPT_BOXES, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER});
    b.push_back({BINDING_LOD_UV, VK_DESCRIPTOR_TYPE_ACCELERATION_STRUCTURE_KHR});
    b.push_back({BINDING_LOD_TABLE, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER});
  }
  if (textures_) SceneTextures::add_bindings(b);
  return b;
}

void GpuScene::bind(gpu::DescriptorSet& set, bool with_lights) const { bind(set, with_lights, false, parity_); }

void GpuScene::bind(gpu::DescriptorSet& set, bool with_lights, bool with_history, int parity) const {
  if (parity != 0 && parity != 1) throw std::invalid_argument("GpuScene::bind: parity must be 0 or 1");
  if (with_history && !keeps_history()) throw std::logic_error("GpuScene::bind: this scene keeps no history");
  const Slot& current = slots_[keeps_history() ? size_t(parity) : 0];
  set.bind_tlas(BINDING_TLAS, current.tlas->handle());
  set.bind_buffer(BINDING_VERTICES, vertices_);
  set.bind_buffer(BINDING_INDICES, indices_);
  set.bind_buffer(BINDING_PRIMITIVES, primitives_);
  set.bind_buffer(BINDING_INSTANCES, current.instances);
  set.bind_buffer(BINDING_MATERIALS, materials_);
  if (with_lights) {
    set.bind_buffer(BINDING_EMITTERS, emitters_);
    set.bind_buffer(BINDING_ALIAS, alias_);
  }
  if (with_history) {
    const Slot& previous = slots_[size_t(1 - parity)];
    set.bind_tlas(BINDING_TLAS_PREV, previous.tlas->handle());
    set.bind_buffer(BINDING_INSTANCES_PREV, previous.instances);
    set.bind_buffer(BINDING_SWEPT_BOXES, swept_);
    // Without LoD groups the table says "off" and the UV TLAS is never traced: the scene's TLAS stands in.
    set.bind_tlas(BINDING_LOD_UV, lod_uv_ ? lod_uv_->tlas().handle() : current.tlas->handle());
    set.bind_buffer(BINDING_LOD_TABLE, lod_uv_ ? lod_uv_->table() : lod_off_table_);
  }
  if (textures_) textures_->bind(set);
}

void GpuScene::set_lod_mapping(const LodMappingSettings& s) {
  lod_mapping_on_ = s.uv;
  if (lod_uv_) lod_uv_->set_settings(s);
}

SceneMemory GpuScene::memory() const {
  SceneMemory m;
  m.geometry = vertices_.size() + indices_.size() + primitives_.size() + materials_.size();
  for (const auto& b : blas_) m.acceleration += b.bytes();
  const Slot& first = slots_[0];
  m.acceleration += first.tlas->bytes() + first.tlas->scratch_bytes();
  m.per_frame = first.instances.size() + emitters_.size() + alias_.size() + (has_punctual() ? first.lights.size() : 0) +
                (light_tree_ ? first.light_tree.size() : 0);
  for (size_t i = 1; i < slots_.size(); ++i)
    m.history += slots_[i].tlas->bytes() + slots_[i].tlas->scratch_bytes() + slots_[i].instances.size() +
                 (has_punctual() ? slots_[i].lights.size() : 0) +
                 (light_tree_ ? slots_[i].light_tree.size() : 0);
  if (keeps_history()) m.history += swept_.size() + lod_off_table_.size();
  if (lod_uv_) m.lod_uv = lod_uv_->bytes();
  if (textures_) m.textures = textures_->bytes();
  if (environment_) m.environment = environment_->bytes();
  if (deformation_) m.deformation = deformation_->bytes();
  return m;
}

}  // namespace strata::render
