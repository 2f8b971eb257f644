#pragma once
// A scene's textures and alpha-tested materials on the device (include/texture_data.h): the
// TextureSet's texels and tables, per material its texture references and alpha test, and per
// vertex the second UV set and tangents where a primitive has them. Uploaded once per scene, and
// only for scenes that have textures or alpha-tested materials: the passes of such a scene run
// their textured variant (include/scene_bridge.glsl, STRATA_TEXTURES); other scenes bind none of it.
#include <cstdint>
#include <span>
#include <vector>

#include "gpu/buffer.h"
#include "gpu/pipeline.h"
#include "scene/scene.h"

namespace strata::render {

// The emission by which the light sampler selects triangle `triangle` of `p` (its power is this
// luminance x area x sides: render/emitters.h), and with which every strategy evaluates the density
// of hitting it: the material's emission, times, with an emissive texture, the triangle's integrated
// texture: the mean of 15 texels spread over the triangle (a barycentric grid) at the mip level where
// the triangle covers about 16 texels (each the box-filtered mean of the texels under it), at least 1/20 of
// the image's mean so that a triangle whose part of the texture is dark at that level still has
// some chance of being sampled. Any positive weight keeps next-event estimation unbiased; what
// matters is that the alias table and the densities at hits use the same one (the scene bridge
// reads it back per triangle: SurfaceMaterial::light_emission).
glm::vec3 triangle_light_emission(const scene::Scene& scene, const scene::Primitive& p, size_t triangle);

class SceneTextures {
 public:
  // Some material reads a texture or is alpha-tested.
  static bool needed(const scene::Scene& scene);
  // alphaMode MASK, and BLEND (rendered as MASK at cutoff 0.5).
  static bool alpha_tested(const scene::Material& m) { return m.alpha_mode != scene::AlphaMode::kOpaque; }

  // `copied_meshes`: the meshes whose vertices follow the rest vertices (SceneDeformation::copied_meshes).
  SceneTextures(const gpu::Context& ctx, const scene::Scene& scene, std::span<const uint32_t> copied_meshes = {});

  // Some material is alpha-tested (SPEC_ALPHA_TEST: rays are not forced opaque).
  bool any_alpha_tested() const { return alpha_tested_; }
  static void add_bindings(std::vector<gpu::Binding>& b);
  void bind(gpu::DescriptorSet& set) const;
  VkDeviceSize bytes() const;

 private:
  gpu::Buffer material_textures_, textures_, levels_, texels_, vertex_extras_, light_emission_;
  bool alpha_tested_ = false;
};

}  // namespace strata::render
