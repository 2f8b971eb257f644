// glTF material textures, samplers, images and alpha modes into Scene materials and
// Scene::textures. Only images a material uses are decoded (PNG or JPEG, image/texture_decode.h),
// once per colour space they are used in (base colour and emissive are sRGB; metallic-roughness and
// normal maps linear), each with its mip chain (scene/texture_mips.h). Images are checked against
// LoadLimits::max_texture_dimension from their header and against max_texture_bytes (the whole
// chain, RGBA8) before they are decoded.
#include <cmath>
#include <map>

#include "image/texture_decode.h"
#include "scene/gltf_convert.h"
#include "scene/gltf_extensions.h"
#include "scene/texture_mips.h"

namespace strata::scene::gltf {
namespace {

constexpr const char* kTransform = "KHR_texture_transform";

std::string describe_number(double v) {
  char buf[48];
  std::snprintf(buf, sizeof buf, "%g", v);
  return buf;
}

float finite_number(const Source& s, const tinygltf::Value& v, const std::string& field) {
  if (!v.IsNumber()) s.fail(field, "must be a number");
  const double d = v.GetNumberAsDouble();
  const float f = to_float(d);
  if (!std::isfinite(f)) s.fail(field, "= " + describe_number(d) + " is not a finite number");
  return f;
}

glm::vec2 finite_pair(const Source& s, const tinygltf::Value& v, const std::string& field) {
  if (!v.IsArray() || v.ArrayLen() != 2) s.fail(field, "must hold 2 numbers");
  return {finite_number(s, v.Get(0), at(field, 0)), finite_number(s, v.Get(1), at(field, 1))};
}

TextureFilter filter_of(const Source& s, int value, const std::string& field, MipFilter* mip) {
  switch (value) {
    case -1: return TextureFilter::kLinear;
    case TINYGLTF_TEXTURE_FILTER_NEAREST: if (mip) *mip = MipFilter::kNone; return TextureFilter::kNearest;
    case TINYGLTF_TEXTURE_FILTER_LINEAR: if (mip) *mip = MipFilter::kNone; return TextureFilter::kLinear;
  }
  if (mip != nullptr) {
    switch (value) {
      case TINYGLTF_TEXTURE_FILTER_NEAREST_MIPMAP_NEAREST: *mip = MipFilter::kNearest; return TextureFilter::kNearest;
      case TINYGLTF_TEXTURE_FILTER_LINEAR_MIPMAP_NEAREST: *mip = MipFilter::kNearest; return TextureFilter::kLinear;
      case TINYGLTF_TEXTURE_FILTER_NEAREST_MIPMAP_LINEAR: *mip = MipFilter::kLinear; return TextureFilter::kNearest;
      case TINYGLTF_TEXTURE_FILTER_LINEAR_MIPMAP_LINEAR: *mip = MipFilter::kLinear; return TextureFilter::kLinear;
    }
  }
  s.fail(field, "= " + std::to_string(value) + " is not a glTF filter");
}

TextureWrap wrap_of(const Source& s, int value, const std::string& field) {
  switch (value) {
    case TINYGLTF_TEXTURE_WRAP_REPEAT: return TextureWrap::kRepeat;
    case TINYGLTF_TEXTURE_WRAP_CLAMP_TO_EDGE: return TextureWrap::kClampToEdge;
    case TINYGLTF_TEXTURE_WRAP_MIRRORED_REPEAT: return TextureWrap::kMirroredRepeat;
  }
  s.fail(field, "= " + std::to_string(value) + " is not a glTF wrap mode");
}

Sampler sampler_of(const Source& s, int index, const std::string& field) {
  Sampler out;
  if (index == -1) return out;
  s.check_index(field, index, s.model.samplers.size(), "samplers");
  const tinygltf::Sampler& in = s.model.samplers[size_t(index)];
  const std::string name = at("samplers", size_t(index));
  out.mag_filter = filter_of(s, in.magFilter, name + ".magFilter", nullptr);
  out.min_filter = filter_of(s, in.minFilter, name + ".minFilter", &out.mip_filter);
  out.wrap_u = wrap_of(s, in.wrapS, name + ".wrapS");
  out.wrap_v = wrap_of(s, in.wrapT, name + ".wrapT");
  return out;
}

// Decodes images and builds textures on first use, per colour space.
class TextureBuilder {
 public:
  TextureBuilder(const Source& s, Scene& scene) : s_(s), scene_(scene) {}

  // The scene texture for glTF texture `index` read in `space`; -1 when it has no image source.
  int32_t texture(int index, ColorSpace space, const std::string& field) {
    s_.check_index(field, index, s_.model.textures.size(), "textures");
    const auto key = std::make_pair(index, space);
    if (const auto it = textures_.find(key); it != textures_.end()) return it->second;
    const tinygltf::Texture& t = s_.model.textures[size_t(index)];
    const std::string name = at("textures", size_t(index));
    if (t.source == -1) {
      ++without_source_;
      return textures_[key] = -1;
    }
    s_.check_index(name + ".source", t.source, s_.model.images.size(), "images");
    Texture out;
    out.sampler = sampler_of(s_, t.sampler, name + ".sampler");
    out.image = image(t.source, space);
    scene_.textures.textures.push_back(out);
    return textures_[key] = int32_t(scene_.textures.textures.size() - 1);
  }

  size_t without_source() const { return without_source_; }

 private:
  std::span<const uint8_t> encoded(const tinygltf::Image& img, const std::string& field) {
    if (img.bufferView >= 0) {
      s_.check_index(field + ".bufferView", img.bufferView, s_.model.bufferViews.size(), "bufferViews");
      const tinygltf::BufferView& view = s_.model.bufferViews[size_t(img.bufferView)];
      s_.check_index(at("bufferViews", size_t(img.bufferView)) + ".buffer", view.buffer, s_.model.buffers.size(),
                     "buffers");
      const std::vector<unsigned char>& data = s_.model.buffers[size_t(view.buffer)].data;
      if (view.byteOffset > data.size() || view.byteLength > data.size() - view.byteOffset) {
        s_.fail(at("bufferViews", size_t(img.bufferView)),
                "(byteOffset " + std::to_string(view.byteOffset) + ", byteLength " +
                    std::to_string(view.byteLength) + ") runs past the end of its buffer");
      }
      return {data.data() + view.byteOffset, view.byteLength};
    }
    if (img.image.empty()) {
      std::string uri = img.uri.size() > 80 ? img.uri.substr(0, 80) + "..." : img.uri;
      s_.fail(field + ".uri", "= '" + uri + "' could not be read (a missing or empty file)");
    }
    return img.image;
  }

  uint32_t image(int index, ColorSpace space) {
    const auto key = std::make_pair(index, space);
    if (const auto it = images_.find(key); it != images_.end()) return it->second;
    const tinygltf::Image& img = s_.model.images[size_t(index)];
    const std::string field = at("images", size_t(index));
    std::string name = !img.name.empty() ? img.name : img.uri.rfind("data:", 0) != 0 ? img.uri : "";
    if (name.size() > 80) name = name.substr(0, 80) + "...";
    const std::string label = name.empty() ? field : field + " ('" + name + "')";
    const std::span<const uint8_t> bytes = encoded(img, field);
    image::ImageSize size;
    try {
      size = image::encoded_size(bytes);
    } catch (const image::ImageError& e) {
      throw SceneError(s_.label + ": " + label + ": " + e.what() + " (glTF textures are PNG or JPEG)");
    }
    const LoadLimits& limits = s_.limits;
    if (size.width > limits.max_texture_dimension || size.height > limits.max_texture_dimension) {
      throw SceneLimitError(s_.label + ": " + label + " is " + std::to_string(size.width) + " x " +
                            std::to_string(size.height) + " texels, over LoadLimits::max_texture_dimension (" +
                            std::to_string(limits.max_texture_dimension) + ")");
    }
    const uint64_t total = scene_.textures.bytes() + 4 * mip_chain_texels(size.width, size.height);
    if (total > limits.max_texture_bytes) {
      throw SceneLimitError(s_.label + ": " + label + " brings the decoded textures (RGBA8 with mip levels) to " +
                            std::to_string(total) + " bytes, over LoadLimits::max_texture_bytes (" +
                            std::to_string(limits.max_texture_bytes) + ")");
    }
    image::Rgba8Image decoded;
    try {
      decoded = image::decode_rgba8(bytes, limits.max_texture_dimension);
    } catch (const image::ImageError& e) {
      throw SceneError(s_.label + ": " + label + ": " + e.what());
    }
    const uint32_t out = add_texture_image(scene_.textures, decoded, space, name.empty() ? field : name);
    return images_[key] = out;
  }

  const Source& s_;
  Scene& scene_;
  std::map<std::pair<int, ColorSpace>, int32_t> textures_;
  std::map<std::pair<int, ColorSpace>, uint32_t> images_;
  size_t without_source_ = 0;
};

struct Counts {
  size_t high_tex_coord = 0;
};

TextureTransform read_transform(const Source& s, const tinygltf::ExtensionMap& extensions,
                                const std::string& field, uint32_t& tex_coord) {
  TextureTransform out;
  const auto it = extensions.find(kTransform);
  if (it == extensions.end()) return out;
  const std::string name = field + ".extensions." + kTransform;
  const tinygltf::Value& v = it->second;
  if (!v.IsObject()) s.fail(name, "must be an object");
  if (v.Has("offset")) out.offset = finite_pair(s, v.Get("offset"), name + ".offset");
  if (v.Has("rotation")) out.rotation = finite_number(s, v.Get("rotation"), name + ".rotation");
  if (v.Has("scale")) out.scale = finite_pair(s, v.Get("scale"), name + ".scale");
  if (v.Has("texCoord")) {
    const tinygltf::Value& t = v.Get("texCoord");
    if (!t.IsInt() || t.Get<int>() < 0) s.fail(name + ".texCoord", "must be a non-negative integer");
    tex_coord = uint32_t(t.Get<int>());
  }
  return out;
}

TextureRef read_ref(const Source& s, TextureBuilder& builder, Counts& counts, int index, int tex_coord,
                    const tinygltf::ExtensionMap& extensions, ColorSpace space, const std::string& field) {
  TextureRef ref;
  if (index == -1) return ref;
  if (tex_coord < 0) s.fail(field + ".texCoord", "must be a non-negative integer");
  uint32_t set = uint32_t(tex_coord);
  ref.transform = read_transform(s, extensions, field, set);
  if (set > 1) {
    ++counts.high_tex_coord;
    return TextureRef{};
  }
  ref.tex_coord = set;
  ref.texture = builder.texture(index, space, field + ".index");
  if (ref.texture < 0) return TextureRef{};
  return ref;
}

AlphaMode alpha_mode_of(const Source& s, const std::string& mode, const std::string& field) {
  if (mode.empty() || mode == "OPAQUE") return AlphaMode::kOpaque;
  if (mode == "MASK") return AlphaMode::kMask;
  if (mode == "BLEND") return AlphaMode::kBlend;
  s.fail(field, "= '" + mode + "' is not OPAQUE, MASK or BLEND");
}

}  // namespace

void convert_material_textures(const Source& s, Scene& scene) {
  TextureBuilder builder(s, scene);
  Counts counts;
  for (size_t i = 0; i < s.model.materials.size(); ++i) {
    const tinygltf::Material& m = s.model.materials[i];
    const std::string field = at("materials", i);
    Material& out = scene.materials[i];
    out.alpha = to_float(m.pbrMetallicRoughness.baseColorFactor[3]);
    out.alpha_mode = alpha_mode_of(s, m.alphaMode, field + ".alphaMode");
    out.alpha_cutoff = to_float(m.alphaCutoff);
    if (!std::isfinite(out.alpha_cutoff) || out.alpha_cutoff < 0.0f)
      s.fail(field + ".alphaCutoff", "= " + describe_number(m.alphaCutoff) + " is not a finite number >= 0");
    const auto& pbr = m.pbrMetallicRoughness;
    out.base_color_texture =
        read_ref(s, builder, counts, pbr.baseColorTexture.index, pbr.baseColorTexture.texCoord,
                 pbr.baseColorTexture.extensions, ColorSpace::kSrgb, field + ".pbrMetallicRoughness.baseColorTexture");
    out.metallic_roughness_texture = read_ref(
        s, builder, counts, pbr.metallicRoughnessTexture.index, pbr.metallicRoughnessTexture.texCoord,
        pbr.metallicRoughnessTexture.extensions, ColorSpace::kLinear,
        field + ".pbrMetallicRoughness.metallicRoughnessTexture");
    out.normal_texture = read_ref(s, builder, counts, m.normalTexture.index, m.normalTexture.texCoord,
                                  m.normalTexture.extensions, ColorSpace::kLinear, field + ".normalTexture");
    out.normal_scale = to_float(m.normalTexture.scale);
    if (!std::isfinite(out.normal_scale))
      s.fail(field + ".normalTexture.scale", "= " + describe_number(m.normalTexture.scale) + " is not finite");
    out.emissive_texture = read_ref(s, builder, counts, m.emissiveTexture.index, m.emissiveTexture.texCoord,
                                    m.emissiveTexture.extensions, ColorSpace::kSrgb, field + ".emissiveTexture");
  }
  if (counts.high_tex_coord > 0) {
    scene.ignored_features.push_back("texCoord 2 or above on " + count_of(counts.high_tex_coord, "texture reference") +
                                     " (sets 0 and 1 are read: those textures are not used)");
  }
  if (builder.without_source() > 0) {
    scene.ignored_features.push_back(count_of(builder.without_source(), "texture") +
                                     " without a PNG or JPEG source (not used)");
  }
}

}  // namespace strata::scene::gltf
