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

// Thrown when scene input exceeds a resource limit (texture bytes, texture dimension): the message
// names the limit. The service answers it with RESOURCE_EXHAUSTED.
struct SceneLimitError : SceneError {
  using SceneError::SceneError;
};

// ---- Textures (glTF textures, samplers and images) ---------------------------------------------
// Laid out to be uploaded as they are: every texel of every mip level of every image in one array
// (TextureSet::texels), images and levels as flat tables indexing into it.

enum class ColorSpace : uint8_t { kLinear = 0, kSrgb = 1 };  // of RGB; alpha is always linear
enum class TextureFilter : uint8_t { kNearest = 0, kLinear = 1 };
enum class MipFilter : uint8_t { kNone = 0, kNearest = 1, kLinear = 2 };  // kNone: level 0 only
enum class TextureWrap : uint8_t { kRepeat = 0, kClampToEdge = 1, kMirroredRepeat = 2 };

// glTF sampler; the defaults are what glTF leaves to the implementation (trilinear, repeat).
struct Sampler {
  TextureFilter mag_filter = TextureFilter::kLinear;
  TextureFilter min_filter = TextureFilter::kLinear;
  MipFilter mip_filter = MipFilter::kLinear;
  TextureWrap wrap_u = TextureWrap::kRepeat;  // glTF wrapS
  TextureWrap wrap_v = TextureWrap::kRepeat;  // glTF wrapT
  bool operator==(const Sampler&) const = default;
};

// One mip level: width x height texels at TextureSet::texels[offset], row-major, top row first.
struct MipLevel {
  uint32_t width = 0;
  uint32_t height = 0;
  uint32_t offset = 0;
  bool operator==(const MipLevel&) const = default;
};

// A decoded image and its mip chain (scene/texture_mips.h). UV (0, 0) is the top-left corner of
// the image, UV (1, 1) the bottom-right, as glTF defines.
struct TextureImage {
  std::string name;  // the glTF image's name, else its URI, else "images[i]"
  ColorSpace color_space = ColorSpace::kSrgb;
  uint32_t first_level = 0;  // into TextureSet::levels
  uint32_t level_count = 0;  // down to 1 x 1
  bool operator==(const TextureImage&) const = default;
};

struct Texture {
  uint32_t image = 0;  // into TextureSet::images
  Sampler sampler;
  bool operator==(const Texture&) const = default;
};

struct TextureSet {
  std::vector<TextureImage> images;
  std::vector<MipLevel> levels;
  std::vector<Texture> textures;
  // RGBA8: R | G << 8 | B << 16 | A << 24 (VK_FORMAT_R8G8B8A8 byte order, GLSL unpackUnorm4x8).
  std::vector<uint32_t> texels;
  uint64_t bytes() const { return uint64_t(texels.size()) * 4; }
  bool operator==(const TextureSet&) const = default;
};

// KHR_texture_transform: uv' = T(offset) R(rotation) S(scale) uv, applied before the lookup.
struct TextureTransform {
  glm::vec2 offset{0.0f};
  float rotation = 0.0f;  // radians; positive turns UVs counter-clockwise as glTF defines
  glm::vec2 scale{1.0f};
  // The 3 x 3 matrix of the transform (its last row is 0, 0, 1).
  glm::mat3 matrix() const;
  bool operator==(const TextureTransform&) const = default;
};

// A material's use of a texture (glTF textureInfo).
struct TextureRef {
  int32_t texture = -1;    // into TextureSet::textures; -1: none
  uint32_t tex_coord = 0;  // 0: Primitive::uvs, 1: Primitive::uvs1 (KHR_texture_transform's override applied)
  TextureTransform transform;
  bool operator==(const TextureRef&) const = default;
};

enum class AlphaMode : uint8_t { kOpaque = 0, kMask = 1, kBlend = 2 };

// glTF metallic-roughness, rendered as Lambert + GGX (see shaders/material/).
struct Material {
  std::string name;
  glm::vec3 base_color{0.8f};
  float metallic = 0.0f;
  float roughness = 1.0f;          // perceptual roughness; GGX alpha = roughness^2
  glm::vec3 emission{0.0f};        // emissiveFactor * KHR_materials_emissive_strength (radiance)
  float specular = 1.0f;           // KHR_materials_specular specularFactor: dielectric F0 = 0.04 * specular
  bool double_sided = false;
  // baseColorFactor's alpha, alphaMode and alphaCutoff. Coverage = alpha x the base colour
  // texture's alpha; MASK keeps a surface where coverage >= alpha_cutoff.
  float alpha = 1.0f;
  AlphaMode alpha_mode = AlphaMode::kOpaque;
  float alpha_cutoff = 0.5f;
  // Textures multiply the factors above, as glTF defines: base colour (sRGB RGB, linear alpha),
  // metallic-roughness (linear; G roughness, B metallic), normal (linear tangent-space normal,
  // xy scaled by normal_scale), emissive (sRGB).
  TextureRef base_color_texture;
  TextureRef metallic_roughness_texture;
  TextureRef normal_texture;
  float normal_scale = 1.0f;
  TextureRef emissive_texture;
  bool operator==(const Material&) const = default;
};

// A glTF morph target of a primitive: per vertex, displacements added to the positions and normals
// in proportion to the target's weight (glTF 2.0 3.7.2.2). `normals` is empty when the target
// leaves the normals alone.
struct MorphTarget {
  std::vector<glm::vec3> positions;
  std::vector<glm::vec3> normals;
  bool operator==(const MorphTarget&) const = default;
};

// One glTF primitive: an indexed triangle list with one material. Attribute arrays have equal length.
struct Primitive {
  std::vector<glm::vec3> positions;
  std::vector<glm::vec3> normals;  // unit length; generated (area-weighted) when the file has none
  std::vector<glm::vec2> uvs;      // TEXCOORD_0; zeros when the file has none
  // TEXCOORD_1, only when a texture of the primitive's material reads set 1; else empty.
  std::vector<glm::vec2> uvs1;
  // TANGENT (xyz unit, w = +-1 the bitangent's sign), only when the material has a normal texture
  // and the file gives tangents; else empty (tangents then follow from the UVs per triangle).
  std::vector<glm::vec4> tangents;
  std::vector<uint32_t> indices;   // 3 per triangle
  uint32_t material = 0;
  // Skinned meshes (JOINTS_0, WEIGHTS_0): per vertex up to 4 joints of the instance's skin and their
  // weights, which sum to 1; both empty when the mesh is not skinned.
  std::vector<glm::uvec4> joints;
  std::vector<glm::vec4> weights;
  // Morph targets, as many as Mesh::weights; empty when the mesh has none.
  std::vector<MorphTarget> targets;
  size_t triangle_count() const { return indices.size() / 3; }
  bool operator==(const Primitive&) const = default;
};

// A glTF mesh. Each LoD level of an object is its own Mesh.
struct Mesh {
  std::string name;
  std::vector<Primitive> primitives;
  // Default morph target weights (glTF mesh.weights), one per target of every primitive; empty
  // when the mesh has no morph targets.
  std::vector<float> weights;
  bool operator==(const Mesh&) const = default;
};

// A glTF skin: the joints a skinned mesh's vertices follow (linear blend skinning). Joint j moves a
// vertex by S_j = inverse(T) J_j B_j, in the object space of the instance whose transform is T,
// where J_j is the joint's joint-to-world transform at the frame (FrameState::joints) and B_j its
// inverse bind matrix; the instance's transform then applies as for any mesh, so the vertex lands at
// J_j B_j v in world space whatever the instance's own transform is (glTF 2.0 3.7.3).
struct Skin {
  std::string name;
  std::vector<glm::mat4> inverse_bind;  // per joint (B_j)
  std::vector<glm::mat4> joints;        // per joint: joint to world at rest (J_j without animation)
  bool operator==(const Skin&) const = default;
};

// A node with a mesh, flattened to a world transform. With MSFT_lod, lod_meshes lists every level
// (0 = finest); the level in use is chosen per frame at run time.
struct Instance {
  std::string name;
  std::vector<uint32_t> lod_meshes;  // at least one entry
  glm::mat4 transform{1.0f};         // object to world
  uint32_t lod = 0;                  // level at frame 0
  // A deforming instance has one level. skin: into Scene::skins, for a mesh with joints and
  // weights (-1: not skinned). morph_weights: its mesh's targets' weights at rest (the node's
  // weights, else the mesh's); empty when the mesh has no targets.
  int32_t skin = -1;
  std::vector<float> morph_weights;
  bool deforms() const { return skin >= 0 || !morph_weights.empty(); }
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

// KHR_lights_punctual. Units as for emission: a point or spot light's intensity (candela) is read
// in the renderer's radiance units per steradian, so a light of intensity I at distance d gives
// irradiance I / d^2 on a surface facing it; a directional light's intensity (lux) is the
// irradiance on a surface facing it. A light shines down its local -Z (spot, directional); a spot's
// falloff is the extension's: full inside inner_cone, zero outside outer_cone, smooth between.
enum class LightType : uint8_t { kDirectional = 0, kPoint = 1, kSpot = 2 };
struct Light {
  std::string name;
  LightType type = LightType::kPoint;
  glm::vec3 color{1.0f};  // linear
  float intensity = 1.0f;
  float range = 0.0f;  // 0: unlimited; else the light fades to zero at this distance
  float inner_cone = 0.0f;             // radians, spot only; 0 <= inner_cone < outer_cone
  float outer_cone = 0.78539816339f;   // radians, spot only; <= pi / 2
  // Light to world at rest: the world transform of the node the light is attached to. The light
  // follows its node: Animation::light_tracks carries the node's animation.
  glm::mat4 transform{1.0f};
  bool operator==(const Light&) const = default;
};

// An equirectangular HDR image as the environment (scene/environment_map.h for the mapping and
// its importance sampling). Row 0 looks straight up (+Y); the image's centre column looks down -Z,
// where a default camera looks, and u grows towards +X from there.
struct EnvironmentMap {
  std::string name;  // the file it came from
  uint32_t width = 0;
  uint32_t height = 0;
  std::vector<glm::vec3> radiance;  // linear, row-major, top row first, before `intensity`
  float intensity = 1.0f;           // scales radiance
  float rotation = 0.0f;            // radians about +Y, counter-clockwise seen from above
  // Importance sampling by luminance x solid angle: texel weights w = Y(radiance) sin(theta) at
  // the texel's centre; per row the CDF over its columns (width + 1 entries, 0 to 1), over the
  // rows the CDF of their sums (height + 1 entries); weight_sum = sum of w (0: a black map).
  std::vector<float> conditional_cdf;
  std::vector<float> marginal_cdf;
  double weight_sum = 0.0;
  bool operator==(const EnvironmentMap&) const = default;
};

// Constant environment radiance seen by rays that escape (and sampled by NEE when non-zero),
// or an environment map.
struct Environment {
  glm::vec3 radiance{0.0f};
  std::optional<EnvironmentMap> map;
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
struct LightTrack {  // replaces the light's transform while it has keys
  uint32_t light = 0;
  std::vector<TransformKey> keys;
  bool operator==(const LightTrack&) const = default;
};
struct JointTrack {  // replaces the joint's joint-to-world transform while it has keys
  uint32_t skin = 0;
  uint32_t joint = 0;
  std::vector<TransformKey> keys;
  bool operator==(const JointTrack&) const = default;
};
struct MorphKey {
  float time = 0.0f;
  std::vector<float> weights;  // one per morph target of the instance's mesh; linear between keys
  bool operator==(const MorphKey&) const = default;
};
struct MorphTrack {  // replaces the instance's morph weights while it has keys
  uint32_t instance = 0;
  std::vector<MorphKey> keys;
  bool operator==(const MorphTrack&) const = default;
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
  std::vector<LightTrack> light_tracks;
  std::vector<JointTrack> joint_tracks;
  std::vector<MorphTrack> morph_tracks;
  bool operator==(const Animation&) const = default;
};

// Everything a frame needs that may change over time: what the renderer consumes per frame.
struct FrameState {
  Camera camera;                      // at the frame's instant, where the shutter closes
  std::vector<glm::mat4> transforms;  // per instance, object to world
  std::vector<uint32_t> lods;         // per instance, level in use
  std::vector<glm::mat4> lights;      // per light, light to world
  // Per instance: a skinned instance's joints, joint to world (its skin's J_j); empty when not skinned.
  std::vector<std::vector<glm::mat4>> joints;
  // Per instance: its morph target weights; empty when its mesh has no targets.
  std::vector<std::vector<float>> morph_weights;
  // Where the shutter opened (scene/shutter.h): over the shutter the camera moves from it to
  // `camera` (RS-supp 3.3.1). None: the frame is an instant (shutter closed, or nothing moved).
  std::optional<Camera> camera_open;
  bool operator==(const FrameState&) const = default;
};

struct Scene {
  std::string name;
  std::vector<Material> materials;
  TextureSet textures;
  std::vector<Mesh> meshes;
  std::vector<Instance> instances;
  std::vector<Skin> skins;
  std::vector<Light> lights;
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
