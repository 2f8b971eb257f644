#include "render/scene_textures.h"

#include "include/bindings.h"
#include "include/texture_data.h"
#include "scene/texture_mips.h"

#include <algorithm>
#include <cmath>

namespace strata::render {
namespace {

uint32_t sampler_bits(const scene::Sampler& s) {
  auto wrap = [](scene::TextureWrap w) {
    switch (w) {
      case scene::TextureWrap::kClampToEdge: return gpu::TEXTURE_WRAP_CLAMP;
      case scene::TextureWrap::kMirroredRepeat: return gpu::TEXTURE_WRAP_MIRROR;
      case scene::TextureWrap::kRepeat: break;
    }
    return gpu::TEXTURE_WRAP_REPEAT;
  };
  uint32_t mip = s.mip_filter == scene::MipFilter::kNone      ? gpu::TEXTURE_MIP_NONE
                 : s.mip_filter == scene::MipFilter::kNearest ? gpu::TEXTURE_MIP_NEAREST
                                                              : gpu::TEXTURE_MIP_LINEAR;
  return (s.mag_filter == scene::TextureFilter::kLinear ? gpu::TEXTURE_MAG_LINEAR : 0u) |
         (s.min_filter == scene::TextureFilter::kLinear ? gpu::TEXTURE_MIN_LINEAR : 0u) | mip << gpu::TEXTURE_MIP_SHIFT |
         wrap(s.wrap_u) << gpu::TEXTURE_WRAP_U_SHIFT | wrap(s.wrap_v) << gpu::TEXTURE_WRAP_V_SHIFT;
}

// The device's texels: every level of every image as linear RGBA16 (unorm, two words a texel),
// sRGB images' RGB decoded here (IEC 61966-2-1, the decode the mip chains were averaged with), so
// that the shaders read a texel with one load and no pow (include/textures.glsl, texel_at).
std::vector<glm::uvec2> linear_texels(const scene::TextureSet& set) {
  std::vector<glm::uvec2> out(set.texels.size());
  auto unorm16 = [](float v) { return uint32_t(std::lround(std::clamp(v, 0.0f, 1.0f) * 65535.0f)); };
  for (const scene::TextureImage& image : set.images) {
    const bool srgb = image.color_space == scene::ColorSpace::kSrgb;
    const scene::MipLevel& last = set.levels[image.first_level + image.level_count - 1];
    const size_t begin = set.levels[image.first_level].offset, end = size_t(last.offset) + size_t(last.width) * last.height;
    for (size_t i = begin; i < end; ++i) {
      const uint32_t t = set.texels[i];
      float c[4];
      for (int k = 0; k < 4; ++k) {
        const uint8_t v = uint8_t(t >> (8 * k));
        c[k] = srgb && k < 3 ? scene::srgb_to_linear(v) : float(v) / 255.0f;
      }
      out[i] = glm::uvec2(unorm16(c[0]) | unorm16(c[1]) << 16, unorm16(c[2]) | unorm16(c[3]) << 16);
    }
  }
  return out;
}

gpu::GpuTextureRef texture_ref(const scene::TextureRef& r) {
  const glm::mat3 m = r.transform.matrix();  // column-major: m[column][row]
  gpu::GpuTextureRef g{};
  g.row0 = glm::vec4(m[0][0], m[1][0], m[2][0], 0.0f);
  g.row1 = glm::vec4(m[0][1], m[1][1], m[2][1], 0.0f);
  g.texture = r.texture;
  g.tex_coord = r.tex_coord;
  return g;
}

// Vertices in GpuScene::upload_geometry's order (every mesh, every primitive) have extras when
// some primitive has a second UV set or tangents.
bool has_vertex_extras(const scene::Scene& scene) {
  for (const auto& mesh : scene.meshes)
    for (const auto& p : mesh.primitives)
      if (!p.uvs1.empty() || !p.tangents.empty()) return true;
  return false;
}

int wrap_texel(int64_t i, int n, scene::TextureWrap mode) {
  if (mode == scene::TextureWrap::kClampToEdge) return int(std::clamp<int64_t>(i, 0, n - 1));
  if (mode == scene::TextureWrap::kMirroredRepeat) {
    int64_t m = i % (2 * int64_t(n));
    if (m < 0) m += 2 * int64_t(n);
    return int(m < n ? m : 2 * int64_t(n) - 1 - m);
  }
  int64_t m = i % n;
  return int(m < 0 ? m + n : m);
}

glm::vec3 texel_rgb(const scene::TextureImage& image, uint32_t texel) {
  glm::vec3 c;
  for (int k = 0; k < 3; ++k) {
    const uint8_t v = uint8_t(texel >> (8 * k));
    c[k] = image.color_space == scene::ColorSpace::kSrgb ? scene::srgb_to_linear(v) : float(v) / 255.0f;
  }
  return c;
}

bool has_emissive_textures(const scene::Scene& scene) {
  for (const auto& m : scene.materials)
    if (m.emissive_texture.texture >= 0) return true;
  return false;
}

}  // namespace

glm::vec3 triangle_light_emission(const scene::Scene& scene, const scene::Primitive& p, size_t triangle) {
  const scene::Material& m = scene.materials[p.material];
  const scene::TextureRef& ref = m.emissive_texture;
  if (ref.texture < 0) return m.emission;
  const scene::TextureSet& set = scene.textures;
  const scene::Texture& tex = set.textures[size_t(ref.texture)];
  const scene::TextureImage& image = set.images[tex.image];
  const std::vector<glm::vec2>& uvs = ref.tex_coord == 1 && !p.uvs1.empty() ? p.uvs1 : p.uvs;
  const glm::mat3 transform = ref.transform.matrix();
  glm::vec2 t[3];
  for (int k = 0; k < 3; ++k) t[k] = glm::vec2(transform * glm::vec3(uvs[p.indices[3 * triangle + size_t(k)]], 1.0f));
  const glm::vec2 a = t[1] - t[0], b = t[2] - t[0];
  const double uv_area = 0.5 * std::abs(double(a.x) * b.y - double(a.y) * b.x);
  const scene::MipLevel& base = set.levels[image.first_level];
  // The level at which the triangle covers about 16 texels (level l has (w h) / 4^l texels over the
  // unit square), read at 15 points spread over the triangle (barycentric grid of side 4).
  const double texels = uv_area * double(base.width) * double(base.height);
  const uint32_t last = image.level_count - 1;
  const uint32_t level = texels > 16.0 ? std::min(last, uint32_t(std::floor(0.5 * std::log2(texels / 16.0)))) : 0u;
  const scene::MipLevel& l = set.levels[image.first_level + level];
  glm::vec3 at_level(0.0f);
  int points = 0;
  for (int i = 0; i < 5; ++i) {
    for (int j = 0; i + j < 5; ++j, ++points) {
      const float b1 = (float(i) + 0.25f) / 5.5f, b2 = (float(j) + 0.25f) / 5.5f;
      glm::vec2 c = (1.0f - b1 - b2) * t[0] + b1 * t[1] + b2 * t[2];
      if (!std::isfinite(c.x) || !std::isfinite(c.y)) c = glm::vec2(0.0f);
      c = glm::clamp(c, glm::vec2(-1e6f), glm::vec2(1e6f));
      const int x = wrap_texel(int64_t(std::floor(double(c.x) * l.width)), int(l.width), tex.sampler.wrap_u);
      const int y = wrap_texel(int64_t(std::floor(double(c.y) * l.height)), int(l.height), tex.sampler.wrap_v);
      at_level += texel_rgb(image, set.texels[l.offset + size_t(y) * l.width + size_t(x)]);
    }
  }
  at_level /= float(points);
  const glm::vec3 mean = texel_rgb(image, set.texels[set.levels[image.first_level + last].offset]);
  return m.emission * glm::max(at_level, 0.05f * mean);
}

bool SceneTextures::needed(const scene::Scene& scene) {
  for (const auto& m : scene.materials) {
    if (alpha_tested(m) || m.base_color_texture.texture >= 0 || m.metallic_roughness_texture.texture >= 0 ||
        m.normal_texture.texture >= 0 || m.emissive_texture.texture >= 0)
      return true;
  }
  return false;
}

SceneTextures::SceneTextures(const gpu::Context& ctx, const scene::Scene& scene, std::span<const uint32_t> copied_meshes) {
  const bool extras = has_vertex_extras(scene);
  std::vector<gpu::GpuMaterialTextures> mats;
  for (const auto& m : scene.materials) {
    gpu::GpuMaterialTextures g{};
    g.slots[gpu::MATERIAL_TEXTURE_BASE_COLOR] = texture_ref(m.base_color_texture);
    g.slots[gpu::MATERIAL_TEXTURE_METALLIC_ROUGHNESS] = texture_ref(m.metallic_roughness_texture);
    g.slots[gpu::MATERIAL_TEXTURE_EMISSIVE] = texture_ref(m.emissive_texture);
    g.slots[gpu::MATERIAL_TEXTURE_NORMAL] = texture_ref(m.normal_texture);
    for (uint32_t k = 0; k < gpu::MATERIAL_TEXTURE_SLOTS; ++k)
      if (g.slots[k].texture >= 0) g.textures |= 1u << k;
    g.alpha = m.alpha;
    // BLEND is rendered as MASK at 0.5 (docs/ARCHITECTURE.md, "glTF content").
    g.alpha_mode = alpha_tested(m) ? gpu::ALPHA_MASK : gpu::ALPHA_OPAQUE;
    g.alpha_cutoff = m.alpha_mode == scene::AlphaMode::kBlend ? 0.5f : m.alpha_cutoff;
    g.normal_scale = m.normal_scale;
    g.flags = extras ? gpu::MATERIAL_VERTEX_EXTRAS : 0u;
    alpha_tested_ = alpha_tested_ || alpha_tested(m);
    mats.push_back(g);
  }
  const scene::TextureSet& set = scene.textures;
  std::vector<gpu::GpuTexture> textures;
  for (const auto& t : set.textures) {
    const scene::TextureImage& image = set.images.at(t.image);
    textures.push_back({image.first_level, image.level_count, sampler_bits(t.sampler), 0u});
  }
  std::vector<gpu::GpuMipLevel> levels;
  for (const auto& l : set.levels) levels.push_back({l.width, l.height, l.offset, 0u});
  std::vector<gpu::GpuVertexExtra> vertex_extras;
  if (extras) {
    for (const auto& mesh : scene.meshes) {
      for (const auto& p : mesh.primitives) {
        for (size_t v = 0; v < p.positions.size(); ++v) {
          gpu::GpuVertexExtra e{};
          if (!p.tangents.empty()) e.tangent = p.tangents[v];
          if (!p.uvs1.empty()) e.uv1 = glm::vec4(p.uvs1[v], 0.0f, 0.0f);
          vertex_extras.push_back(e);
        }
      }
    }
    // The deforming instances' vertex copies (render/scene_deform.h) have their mesh's TEXCOORD_1;
    // their tangents are left to the deformed triangle (dP/du, include/scene_bridge_textures.glsl),
    // since a rest tangent does not turn with a skinned or morphed normal.
    for (uint32_t m : copied_meshes) {
      for (const auto& p : scene.meshes[m].primitives) {
        for (size_t v = 0; v < p.positions.size(); ++v) {
          gpu::GpuVertexExtra e{};
          if (!p.uvs1.empty()) e.uv1 = glm::vec4(p.uvs1[v], 0.0f, 0.0f);
          vertex_extras.push_back(e);
        }
      }
    }
  }
  std::vector<glm::vec4> light_emission;  // per triangle in GpuScene's order (its index array / 3)
  if (has_emissive_textures(scene)) {
    for (const auto& mesh : scene.meshes)
      for (const auto& p : mesh.primitives)
        for (size_t tri = 0; tri < p.triangle_count(); ++tri) light_emission.emplace_back(triangle_light_emission(scene, p, tri), 0.0f);
  }
  constexpr auto usage = gpu::k_storage_usage;
  material_textures_ = gpu::make_buffer<gpu::GpuMaterialTextures>(ctx, mats, usage, gpu::Memory::Device, "material textures");
  textures_ = gpu::make_buffer<gpu::GpuTexture>(ctx, textures, usage, gpu::Memory::Device, "textures");
  levels_ = gpu::make_buffer<gpu::GpuMipLevel>(ctx, levels, usage, gpu::Memory::Device, "texture levels");
  texels_ = gpu::make_buffer<glm::uvec2>(ctx, linear_texels(set), usage, gpu::Memory::Device, "texels");
  vertex_extras_ = gpu::make_buffer<gpu::GpuVertexExtra>(ctx, vertex_extras, usage, gpu::Memory::Device, "vertex extras");
  light_emission_ = gpu::make_buffer<glm::vec4>(ctx, light_emission, usage, gpu::Memory::Device, "triangle light emission");
}

void SceneTextures::add_bindings(std::vector<gpu::Binding>& b) {
  for (uint32_t binding : {BINDING_MATERIAL_TEXTURES, BINDING_TEXTURES, BINDING_TEXTURE_LEVELS, BINDING_TEXELS, BINDING_VERTEX_EXTRAS,
                           BINDING_LIGHT_EMISSION})
    b.push_back({binding, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER});
}

void SceneTextures::bind(gpu::DescriptorSet& set) const {
  set.bind_buffer(BINDING_MATERIAL_TEXTURES, material_textures_);
  set.bind_buffer(BINDING_TEXTURES, textures_);
  set.bind_buffer(BINDING_TEXTURE_LEVELS, levels_);
  set.bind_buffer(BINDING_TEXELS, texels_);
  set.bind_buffer(BINDING_VERTEX_EXTRAS, vertex_extras_);
  set.bind_buffer(BINDING_LIGHT_EMISSION, light_emission_);
}

VkDeviceSize SceneTextures::bytes() const {
  return material_textures_.size() + textures_.size() + levels_.size() + texels_.size() + vertex_extras_.size() +
         light_emission_.size();
}

}  // namespace strata::render
