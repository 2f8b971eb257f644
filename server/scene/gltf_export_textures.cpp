#include "scene/gltf_export_textures.h"

#include <algorithm>
#include <cstring>
#include <span>

#include "image/image.h"

namespace strata::scene::gltf {
namespace {

constexpr const char* kTransform = "KHR_texture_transform";

int gltf_filter(TextureFilter f) {
  return f == TextureFilter::kNearest ? TINYGLTF_TEXTURE_FILTER_NEAREST : TINYGLTF_TEXTURE_FILTER_LINEAR;
}

int gltf_min_filter(TextureFilter f, MipFilter mip) {
  const bool nearest = f == TextureFilter::kNearest;
  switch (mip) {
    case MipFilter::kNone: return gltf_filter(f);
    case MipFilter::kNearest:
      return nearest ? TINYGLTF_TEXTURE_FILTER_NEAREST_MIPMAP_NEAREST : TINYGLTF_TEXTURE_FILTER_LINEAR_MIPMAP_NEAREST;
    case MipFilter::kLinear:
      return nearest ? TINYGLTF_TEXTURE_FILTER_NEAREST_MIPMAP_LINEAR : TINYGLTF_TEXTURE_FILTER_LINEAR_MIPMAP_LINEAR;
  }
  return TINYGLTF_TEXTURE_FILTER_LINEAR_MIPMAP_LINEAR;
}

int gltf_wrap(TextureWrap w) {
  switch (w) {
    case TextureWrap::kRepeat: return TINYGLTF_TEXTURE_WRAP_REPEAT;
    case TextureWrap::kClampToEdge: return TINYGLTF_TEXTURE_WRAP_CLAMP_TO_EDGE;
    case TextureWrap::kMirroredRepeat: return TINYGLTF_TEXTURE_WRAP_MIRRORED_REPEAT;
  }
  return TINYGLTF_TEXTURE_WRAP_REPEAT;
}

tinygltf::Value pair(glm::vec2 v) { return tinygltf::Value(tinygltf::Value::Array{tinygltf::Value(double(v.x)), tinygltf::Value(double(v.y))}); }

// A textureInfo's index, texCoord and, unless it is the identity, its KHR_texture_transform.
template <class Info>
void set_ref(const TextureRef& ref, Info& info, std::vector<std::string>& used) {
  info.index = ref.texture;
  info.texCoord = int(ref.tex_coord);
  if (ref.transform == TextureTransform{}) return;
  tinygltf::Value::Object t;
  if (ref.transform.offset != glm::vec2(0.0f)) t["offset"] = pair(ref.transform.offset);
  if (ref.transform.rotation != 0.0f) t["rotation"] = tinygltf::Value(double(ref.transform.rotation));
  if (ref.transform.scale != glm::vec2(1.0f)) t["scale"] = pair(ref.transform.scale);
  info.extensions[kTransform] = tinygltf::Value(t);
  if (std::find(used.begin(), used.end(), kTransform) == used.end()) used.emplace_back(kTransform);
}

}  // namespace

int append_view(tinygltf::Model& model, const uint8_t* bytes, size_t size) {
  std::vector<unsigned char>& buffer = model.buffers[0].data;
  buffer.resize((buffer.size() + 3) & ~size_t{3});
  tinygltf::BufferView view;
  view.buffer = 0;
  view.byteOffset = buffer.size();
  view.byteLength = size;
  buffer.insert(buffer.end(), bytes, bytes + size);
  model.bufferViews.push_back(view);
  return int(model.bufferViews.size() - 1);
}

void export_textures(tinygltf::Model& model, const TextureSet& set) {
  for (const TextureImage& image : set.images) {
    const MipLevel& l = set.levels[image.first_level];
    const std::vector<uint8_t> png = image::encode_png_rgba8(
        std::span<const uint32_t>(set.texels.data() + l.offset, size_t(l.width) * l.height), l.width, l.height);
    tinygltf::Image out;
    out.name = image.name;
    out.mimeType = "image/png";
    out.bufferView = append_view(model, png.data(), png.size());
    model.images.push_back(out);
  }
  for (const Texture& t : set.textures) {
    tinygltf::Sampler s;
    s.magFilter = gltf_filter(t.sampler.mag_filter);
    s.minFilter = gltf_min_filter(t.sampler.min_filter, t.sampler.mip_filter);
    s.wrapS = gltf_wrap(t.sampler.wrap_u);
    s.wrapT = gltf_wrap(t.sampler.wrap_v);
    model.samplers.push_back(s);
    tinygltf::Texture out;
    out.source = int(t.image);
    out.sampler = int(model.samplers.size() - 1);
    model.textures.push_back(out);
  }
}

void export_material_textures(const Material& m, tinygltf::Material& out, std::vector<std::string>& used) {
  out.pbrMetallicRoughness.baseColorFactor[3] = m.alpha;
  out.alphaMode = m.alpha_mode == AlphaMode::kMask ? "MASK" : m.alpha_mode == AlphaMode::kBlend ? "BLEND" : "OPAQUE";
  out.alphaCutoff = m.alpha_cutoff;
  if (m.base_color_texture.texture >= 0) set_ref(m.base_color_texture, out.pbrMetallicRoughness.baseColorTexture, used);
  if (m.metallic_roughness_texture.texture >= 0)
    set_ref(m.metallic_roughness_texture, out.pbrMetallicRoughness.metallicRoughnessTexture, used);
  if (m.normal_texture.texture >= 0) {
    set_ref(m.normal_texture, out.normalTexture, used);
    out.normalTexture.scale = m.normal_scale;
  }
  if (m.emissive_texture.texture >= 0) set_ref(m.emissive_texture, out.emissiveTexture, used);
}

tinygltf::Value export_environment_map(tinygltf::Model& model, const EnvironmentMap& map) {
  std::vector<float> rgb;
  rgb.reserve(map.radiance.size() * 3);
  for (const glm::vec3& c : map.radiance) rgb.insert(rgb.end(), {c.r, c.g, c.b});
  const int view = append_view(model, reinterpret_cast<const uint8_t*>(rgb.data()), rgb.size() * sizeof(float));
  return tinygltf::Value(tinygltf::Value::Object{
      {"name", tinygltf::Value(map.name)},
      {"width", tinygltf::Value(int(map.width))},
      {"height", tinygltf::Value(int(map.height))},
      {"intensity", tinygltf::Value(double(map.intensity))},
      {"rotation", tinygltf::Value(double(map.rotation))},
      {"bufferView", tinygltf::Value(view)},
  });
}

}  // namespace strata::scene::gltf
