// glTF textures on the host: images decoded (PNG, JPEG) with their orientation and colour space,
// mip chains averaged in linear space, samplers, KHR_texture_transform, alpha modes; bad images and
// limits refused naming the field and the limit.
#include <filesystem>
#include <fstream>

#include <gtest/gtest.h>

#include "gltf_test_builder.h"
#include "image/image.h"
#include "image/texture_decode.h"
#include "scene/scene_io.h"
#include "scene/texture_mips.h"
#include "scene/unrendered.h"

namespace strata::scene {
namespace {

using nlohmann::json;
using testing::TestGltf;

uint32_t rgba(uint8_t r, uint8_t g, uint8_t b, uint8_t a = 255) {
  return uint32_t(r) | uint32_t(g) << 8 | uint32_t(b) << 16 | uint32_t(a) << 24;
}

// 2 x 2: top row red, green; bottom row blue, grey 128.
std::vector<uint8_t> known_png() {
  const std::vector<uint8_t> rgb = {255, 0, 0, 0, 255, 0, 0, 0, 255, 128, 128, 128};
  return image::encode_png_rgb8(rgb, 2, 2);
}

// A quad whose material samples `image_bytes` as its base colour (the image in a bufferView).
TestGltf textured_quad(const std::vector<uint8_t>& image_bytes) {
  TestGltf g;
  const int uv = g.floats({0, 1, 1, 1, 1, 0, 0, 0}, "VEC2", 2);
  g.node({{"mesh", g.mesh({{"attributes", {{"POSITION", g.quad_positions()}, {"TEXCOORD_0", uv}}},
                           {"indices", g.quad_indices()},
                           {"material", 0}})}});
  while (g.bin.size() % 4 != 0) g.bin.push_back(0);
  const size_t offset = g.bin.size();
  g.bin.insert(g.bin.end(), image_bytes.begin(), image_bytes.end());
  g.doc["bufferViews"].push_back({{"buffer", 0}, {"byteOffset", offset}, {"byteLength", image_bytes.size()}});
  g.doc["images"] = json::array({{{"bufferView", g.doc["bufferViews"].size() - 1}, {"mimeType", "image/png"}}});
  g.doc["textures"] = json::array({{{"source", 0}}});
  g.doc["materials"] = json::array({{{"pbrMetallicRoughness", {{"baseColorTexture", {{"index", 0}}}}}}});
  return g;
}

std::string error_of(const TestGltf& g, const LoadLimits& limits = {}) {
  try {
    load_glb_bytes(g.glb(), "t.glb", limits);
  } catch (const SceneError& e) {
    return e.what();
  }
  return "(loaded without error)";
}

::testing::AssertionResult contains(const std::string& text, const std::string& expected) {
  if (text.find(expected) != std::string::npos) return ::testing::AssertionSuccess();
  return ::testing::AssertionFailure() << "expected '" << expected << "' in '" << text << "'";
}

TEST(GltfTextures, KnownTexelsKeepTheirOrientationAndTheMipAveragesInLinearSpace) {
  const Scene s = load_glb_bytes(textured_quad(known_png()).glb(), "t.glb");
  ASSERT_EQ(s.textures.textures.size(), 1u);
  ASSERT_EQ(s.textures.images.size(), 1u);
  const TextureImage& image = s.textures.images[0];
  EXPECT_EQ(image.color_space, ColorSpace::kSrgb);
  ASSERT_EQ(image.level_count, 2u);
  const MipLevel& top = s.textures.levels[image.first_level];
  EXPECT_EQ(top.width, 2u);
  EXPECT_EQ(top.height, 2u);
  // Row-major, top row first: UV (0, 0) is the top-left texel.
  EXPECT_EQ(s.textures.texels[top.offset + 0], rgba(255, 0, 0));
  EXPECT_EQ(s.textures.texels[top.offset + 1], rgba(0, 255, 0));
  EXPECT_EQ(s.textures.texels[top.offset + 2], rgba(0, 0, 255));
  EXPECT_EQ(s.textures.texels[top.offset + 3], rgba(128, 128, 128));
  // The 1 x 1 level: each channel the sRGB encoding of the mean of the linear values.
  const MipLevel& last = s.textures.levels[image.first_level + 1];
  EXPECT_EQ(last.width, 1u);
  const uint8_t c = linear_to_srgb((1.0f + srgb_to_linear(128)) / 4.0f);
  EXPECT_EQ(s.textures.texels[last.offset], rgba(c, c, c));
  EXPECT_GT(c, 140);  // averaging the sRGB bytes instead would give (255 + 128) / 4 = 96
  EXPECT_NEAR(srgb_to_linear(128), 0.2158605f, 1e-6f);
  EXPECT_EQ(s.materials[0].base_color_texture.texture, 0);
  const std::string unrendered = [&] {
    std::string t;
    for (const auto& f : unrendered_features(s)) t += f + "\n";
    return t;
  }();
  EXPECT_FALSE(contains(unrendered, "baseColorTexture")) << unrendered;  // sampled
}

// tests/data/textures/gradient_8x8.jpg: texel i (row-major) = (4i, 255 - 4i, 32 (i % 8)), JPEG
// quality 90 (written with stb_image_write).
TEST(GltfTextures, JpegDecodesTopRowFirst) {
  std::ifstream in(std::string(STRATA_TEST_DATA_DIR) + "/textures/gradient_8x8.jpg", std::ios::binary);
  const std::vector<uint8_t> bytes((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  ASSERT_EQ(image::sniff_format(bytes), image::EncodedFormat::kJpeg);
  const image::Rgba8Image img = image::decode_rgba8(bytes, 8);
  ASSERT_EQ(img.width, 8u);
  ASSERT_EQ(img.height, 8u);
  // Chroma subsampling smears single texels, so compare corners: a flipped image would start with
  // the bottom row (R about 224).
  const auto red = [&](uint32_t i) { return int(img.texels[i] & 255); };
  const auto green = [&](uint32_t i) { return int((img.texels[i] >> 8) & 255); };
  EXPECT_LT(red(0), 60);
  EXPECT_GT(green(0), 200);
  EXPECT_GT(red(63), 200);
  EXPECT_LT(green(63), 60);
  EXPECT_LT(red(7), red(56));  // row order, not only column order
  EXPECT_EQ(img.texels[0] >> 24, 255u);
  EXPECT_THROW(image::decode_rgba8(bytes, 7), image::ImageError);  // over the largest dimension
}

TEST(GltfTextures, SamplersTransformsTexCoordSetsAndAlphaModes) {
  TestGltf g = textured_quad(known_png());
  const int uv1 = g.floats({0, 0, 1, 0, 1, 1, 0, 1}, "VEC2", 2);
  g.doc["meshes"][0]["primitives"][0]["attributes"]["TEXCOORD_1"] = uv1;
  g.doc["samplers"] = json::array({{{"magFilter", 9728}, {"minFilter", 9985}, {"wrapS", 33071}, {"wrapT", 33648}}});
  g.doc["textures"][0]["sampler"] = 0;
  g.doc["materials"][0]["pbrMetallicRoughness"]["baseColorTexture"]["extensions"] = {
      {"KHR_texture_transform", {{"offset", {0.5, 0.25}}, {"rotation", 1.5}, {"scale", {2, 3}}, {"texCoord", 1}}}};
  g.doc["materials"][0]["normalTexture"] = {{"index", 0}, {"scale", 0.5}};
  g.doc["materials"][0]["alphaMode"] = "MASK";
  g.doc["materials"][0]["alphaCutoff"] = 0.25;
  const Scene s = load_glb_bytes(g.glb(), "t.glb");
  const Material& m = s.materials[0];
  EXPECT_EQ(m.alpha_mode, AlphaMode::kMask);
  EXPECT_FLOAT_EQ(m.alpha_cutoff, 0.25f);
  EXPECT_EQ(m.base_color_texture.tex_coord, 1u);
  EXPECT_EQ(m.base_color_texture.transform.offset, glm::vec2(0.5f, 0.25f));
  EXPECT_FLOAT_EQ(m.base_color_texture.transform.rotation, 1.5f);
  EXPECT_EQ(m.base_color_texture.transform.scale, glm::vec2(2.0f, 3.0f));
  // The matrix maps UV (1, 0) to offset + R (scale.x, 0) with R = [cos sin; -sin cos].
  const glm::vec3 mapped = m.base_color_texture.transform.matrix() * glm::vec3(1, 0, 1);
  EXPECT_NEAR(mapped.x, 0.5f + 2.0f * std::cos(1.5f), 1e-5f);
  EXPECT_NEAR(mapped.y, 0.25f - 2.0f * std::sin(1.5f), 1e-5f);
  EXPECT_FLOAT_EQ(m.normal_scale, 0.5f);
  // The normal map reads the same image in linear space: a second image entry.
  EXPECT_EQ(s.textures.images.size(), 2u);
  EXPECT_EQ(s.textures.images[size_t(s.textures.textures[size_t(m.normal_texture.texture)].image)].color_space,
            ColorSpace::kLinear);
  const Sampler& sampler = s.textures.textures[0].sampler;
  EXPECT_EQ(sampler.mag_filter, TextureFilter::kNearest);
  EXPECT_EQ(sampler.min_filter, TextureFilter::kLinear);
  EXPECT_EQ(sampler.mip_filter, MipFilter::kNearest);
  EXPECT_EQ(sampler.wrap_u, TextureWrap::kClampToEdge);
  EXPECT_EQ(sampler.wrap_v, TextureWrap::kMirroredRepeat);
  const Primitive& p = s.meshes[0].primitives[0];
  EXPECT_EQ(p.uvs1.size(), 4u);
  EXPECT_TRUE(p.tangents.empty());  // the file gives none
}

TEST(GltfTextures, ScenesWithoutTexturesKeepNoTextureData) {
  const Scene s = builtin_scene("cornell");
  EXPECT_TRUE(s.textures.texels.empty());
  for (const Mesh& mesh : s.meshes) {
    for (const Primitive& p : mesh.primitives) {
      EXPECT_TRUE(p.uvs1.empty());
      EXPECT_TRUE(p.tangents.empty());
    }
  }
}

TEST(GltfTextures, BadImagesAreRefusedNamingTheImage) {
  std::vector<uint8_t> truncated = known_png();
  truncated.resize(truncated.size() / 2);
  EXPECT_TRUE(contains(error_of(textured_quad(truncated)), "t.glb: images[0]: cannot decode the PNG image"));

  std::vector<uint8_t> garbage = {0x89, 'P', 'N', 'G', 0x0D, 0x0A, 0x1A, 0x0A, 1, 2, 3};
  EXPECT_TRUE(contains(error_of(textured_quad(garbage)), "t.glb: images[0]: cannot read the PNG image's header"));

  const std::vector<uint8_t> gif = {'G', 'I', 'F', '8', '9', 'a', 1, 0, 1, 0, 0, 0, 0};
  EXPECT_TRUE(contains(error_of(textured_quad(gif)),
                       "t.glb: images[0]: unsupported image type: a GIF image (glTF textures are PNG or JPEG)"));

  TestGltf g = textured_quad(known_png());
  g.doc["bufferViews"].back()["byteLength"] = 1 << 20;
  EXPECT_TRUE(contains(error_of(g), "runs past the end of its buffer"));

  g = textured_quad(known_png());
  g.doc["materials"][0]["pbrMetallicRoughness"]["baseColorTexture"]["extensions"] = {
      {"KHR_texture_transform", {{"rotation", 1e300}}}};
  EXPECT_TRUE(contains(error_of(g), "materials[0].pbrMetallicRoughness.baseColorTexture.extensions."
                                    "KHR_texture_transform.rotation = 1e+300 is not a finite number"));
  g = textured_quad(known_png());
  g.doc["materials"][0]["alphaMode"] = "CUTOUT";
  EXPECT_TRUE(contains(error_of(g), "materials[0].alphaMode = 'CUTOUT' is not OPAQUE, MASK or BLEND"));
  g = textured_quad(known_png());
  g.doc["materials"][0]["pbrMetallicRoughness"]["baseColorFactor"] = {1, 1, 1, 1e300};
  EXPECT_TRUE(contains(error_of(g), "materials[0].alpha is not finite"));
}

TEST(GltfTextures, MissingImageFilesAreRefusedNamingTheUri) {
  const std::filesystem::path dir = std::filesystem::temp_directory_path() / "strata_gltf_textures_test";
  std::filesystem::create_directories(dir);
  TestGltf g = textured_quad(known_png());
  g.doc["images"][0] = {{"uri", "nowhere.png"}};
  std::ofstream(dir / "missing.gltf") << g.text();
  try {
    load_gltf_file(dir / "missing.gltf");
    ADD_FAILURE() << "loaded";
  } catch (const SceneError& e) {
    EXPECT_TRUE(contains(e.what(), "images[0].uri = 'nowhere.png' could not be read"));
  }
  std::filesystem::remove_all(dir);
}

TEST(GltfTextures, TexturesOverTheLimitsAreRefusedNamingTheLimit) {
  LoadLimits limits;
  limits.max_texture_dimension = 1;
  try {
    load_glb_bytes(textured_quad(known_png()).glb(), "t.glb", limits);
    ADD_FAILURE() << "loaded";
  } catch (const SceneLimitError& e) {
    EXPECT_TRUE(contains(e.what(), "t.glb: images[0] is 2 x 2 texels, over LoadLimits::max_texture_dimension (1)"));
  }
  limits = LoadLimits{};
  limits.max_texture_bytes = 19;  // the chain takes (4 + 1) x 4 = 20 bytes
  try {
    load_glb_bytes(textured_quad(known_png()).glb(), "t.glb", limits);
    ADD_FAILURE() << "loaded";
  } catch (const SceneLimitError& e) {
    EXPECT_TRUE(contains(e.what(), "brings the decoded textures (RGBA8 with mip levels) to 20 bytes, over "
                                   "LoadLimits::max_texture_bytes (19)"));
  }
  limits.max_texture_bytes = 20;
  EXPECT_NO_THROW(load_glb_bytes(textured_quad(known_png()).glb(), "t.glb", limits));
}

}  // namespace
}  // namespace strata::scene
