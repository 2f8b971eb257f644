#pragma once
// The CPU scene model shared by loaders, built-in scenes, exporters and the GPU upload.
// Conventions (those of glTF 2.0): right-handed, +Y up, metres; cameras look down their local -Z
// with +Y up; triangles wind counter-clockwise seen from their front face; an emissive surface
// emits from its front face only unless its material is double-sided.
#include <cstdint>
#include <optional>
#include <stdexcept>
#include <string>
#include <vector>

#include <glm/glm.hpp>
#include <glm/gtc/quaternion.hpp>

namespace strata::scene {

// Thrown for every problem with scene input: the message names the file, the field and the limit.
struct SceneError : std::runtime_error {
  using std::runtime_error::runtime_error;
};

// glTF metallic-roughness, rendered as Lambert + GGX (see shaders/material/).
struct Material {
  std::string name;
  glm::vec3 base_color{0.8f};
  float metallic = 0.0f;
  float roughness = 1.0f;          // perceptual roughness; GGX alpha = roughness^2
  glm::vec3 emission{0.0f};        // emissiveFactor * KHR_materials_emissive_strength (radiance)
  float specular = 1.0f;           // KHR_materials_specular specularFactor: dielectric F0 = 0.04 * specular
  bool double_sided = false;
  bool operator==(const Material&) const = default;
};

// One glTF primitive: an indexed triangle list with one material. Attribute arrays have equal length.
struct Primitive {
  std::vector<glm::vec3> positions;
  std::vector<glm::vec3> normals;  // unit length; generated (area-weighted) when the file has none
  std::vector<glm::vec2> uvs;      // TEXCOORD_0; zeros when the file has none
  std::vector<uint32_t> indices;   // 3 per triangle
  uint32_t material = 0;
  size_t triangle_count() const { return indices.size() / 3; }
  bool operator==(const Primitive&) const = default;
};

// A glTF mesh. Each LoD level of an object is its own Mesh.
struct Mesh {
  std::string name;
  std::vector<Primitive> primitives;
  bool operator==(const Mesh&) const = default;
};

// A node with a mesh, flattened to a world transform. With MSFT_lod, lod_meshes lists every level
// (0 = finest); the level in use is chosen per frame at run time.
struct Instance {
  std::string name;
  std::vector<uint32_t> lod_meshes;  // at least one entry
  glm::mat4 transform{1.0f};         // object to world
  uint32_t lod = 0;                  // level at frame 0
  bool operator==(const Instance&) const = default;
};

struct Camera {
  glm::vec3 position{0.0f, 0.0f, 5.0f};
  glm::quat orientation{1.0f, 0.0f, 0.0f, 0.0f};  // (w, x, y, z)
  float yfov = 0.8f;             // vertical field of view, radians
  float aperture = 0.0f;         // thin-lens radius in metres; 0 = pinhole
  float focus_distance = 1.0f;   // metres along the view direction
  // Fraction of the frame interval the shutter is open, ending at the frame's instant (motion
  // blur, RS-main 4.4); 0 = the frame is an instant.
  float shutter = 0.0f;
  bool operator==(const Camera&) const = default;
};

// Constant environment radiance seen by rays that escape (and sampled by NEE when non-zero).
struct Environment {
  glm::vec3 radiance{0.0f};
  bool operator==(const Environment&) const = default;
};

// Default animation, keyed in seconds; frame f is at time f / frames_per_second.
// Between keys: linear for vectors and scalars, slerp for rotations; clamped outside the keys.
struct CameraKey {
  float time = 0.0f;
  glm::vec3 position{0.0f};
  glm::quat orientation{1.0f, 0.0f, 0.0f, 0.0f};
  bool operator==(const CameraKey&) const = default;
};
struct TransformKey {
  float time = 0.0f;
  glm::vec3 translation{0.0f};
  glm::quat rotation{1.0f, 0.0f, 0.0f, 0.0f};
  glm::vec3 scale{1.0f};
  bool operator==(const TransformKey&) const = default;
};
struct InstanceTrack {  // replaces the instance's transform while it has keys
  uint32_t instance = 0;
  std::vector<TransformKey> keys;
  bool operator==(const InstanceTrack&) const = default;
};
struct LodKey {  // from `time` on, `instance` uses `level`
  float time = 0.0f;
  uint32_t instance = 0;
  uint32_t level = 0;
  bool operator==(const LodKey&) const = default;
};
struct Animation {
  float frames_per_second = 30.0f;
  std::vector<CameraKey> camera;  // empty: camera stays still
  std::vector<InstanceTrack> tracks;
  std::vector<LodKey> lod_schedule;  // sorted by time
  bool operator==(const Animation&) const = default;
};

// Everything a frame needs that may change over time: what the renderer consumes per frame.
struct FrameState {
  Camera camera;                      // at the frame's instant, where the shutter closes
  std::vector<glm::mat4> transforms;  // per instance, object to world
  std::vector<uint32_t> lods;         // per instance, level in use
  // Where the shutter opened (scene/shutter.h): over the shutter the camera moves from it to
  // `camera` (RS-supp 3.3.1). None: the frame is an instant (shutter closed, or nothing moved).
  std::optional<Camera> camera_open;
  bool operator==(const FrameState&) const = default;
};

struct Scene {
  std::string name;
  std::vector<Material> materials;
  std::vector<Mesh> meshes;
  std::vector<Instance> instances;
  Camera camera;
  Environment environment;
  Animation animation;
  // What the source file holds that the scene model leaves out, one phrase each
  // ("KHR_materials_clearcoat on 3 materials (rendered without the coat)"); empty for built-in
  // scenes. scene/unrendered.h adds what the model keeps but the renderer does not draw.
  std::vector<std::string> ignored_features;

  // The scene's state at frame `frame` of its default animation.
  FrameState frame_state(uint32_t frame) const;
  // Throws SceneError when indices are out of range, arrays disagree in length, or numbers are
  // not finite. Loaders and built-in generators call it before returning.
  void validate() const;
  size_t triangle_count() const;  // over every mesh, every LoD level
  bool operator==(const Scene&) const = default;
};

}  // namespace strata::scene
