// Textures and alpha-tested materials on the device: a 2 x 2 base colour texture on a quad facing
// the camera, lit by a constant white environment (Lambert without a specular lobe, paths of at most
// two segments: every pixel's expectation is its texel's linear colour), read back per quadrant for
// the texture's orientation (UV (0, 0) is the image's top-left corner) and its sRGB decoding; and an
// alpha-masked quad in front of another, whose transparent half shows what lies behind it.
#include <glm/glm.hpp>

#include "gpu/gpu_context.h"
#include "image/texture_decode.h"
#include "render/renderer.h"
#include "scene/texture_mips.h"

namespace strata::test {
namespace {

uint32_t rgba(uint8_t r, uint8_t g, uint8_t b, uint8_t a = 255) {
  return uint32_t(r) | uint32_t(g) << 8 | uint32_t(b) << 16 | uint32_t(a) << 24;
}

// A quad of half size h in the plane z = z0 facing +Z, its top-left corner at UV (0, 0) as glTF
// maps images.
scene::Mesh uv_quad(float h, float z0, uint32_t material) {
  scene::Primitive p;
  p.positions = {{-h, -h, z0}, {h, -h, z0}, {h, h, z0}, {-h, h, z0}};
  p.normals.assign(4, glm::vec3(0, 0, 1));
  p.uvs = {{0, 1}, {1, 1}, {1, 0}, {0, 0}};
  p.indices = {0, 1, 2, 0, 2, 3};
  p.material = material;
  scene::Mesh m;
  m.name = "quad";
  m.primitives.push_back(p);
  return m;
}

scene::Material lambert(glm::vec3 base) {
  scene::Material m;
  m.base_color = base;
  m.specular = 0.0f;
  m.roughness = 1.0f;
  return m;
}

// A texture of `image` with nearest magnification.
int32_t add_texture(scene::Scene& s, const image::Rgba8Image& image, scene::ColorSpace space) {
  scene::Texture t;
  t.image = scene::add_texture_image(s.textures, image, space, "known");
  t.sampler.mag_filter = scene::TextureFilter::kNearest;
  s.textures.textures.push_back(t);
  return int32_t(s.textures.textures.size() - 1);
}

// The camera at (0, 0, 2 / tan(0.4)) looking down -Z: a quad of half size 1 at z = 0 fills the
// middle half of a square image.
void frame_quad(scene::Scene& s) {
  s.camera.position = {0.0f, 0.0f, 2.0f / std::tan(0.4f)};
  s.camera.yfov = 0.8f;
  s.environment.radiance = glm::vec3(1.0f);
}

void add_instance(scene::Scene& s, scene::Mesh mesh) {
  s.meshes.push_back(std::move(mesh));
  scene::Instance inst;
  inst.name = "quad " + std::to_string(s.instances.size());
  inst.lod_meshes = {uint32_t(s.meshes.size() - 1)};
  s.instances.push_back(inst);
}

constexpr uint32_t kSize = 32;

image::Image render(const scene::Scene& s) {
  render::RenderSettings rs;
  rs.width = kSize;
  rs.height = kSize;
  rs.spp = 64;
  rs.max_depth = 2;
  rs.seed = 5;
  render::Renderer renderer(gpu_context(), s, rs);
  return renderer.render(s.frame_state(0), 0).image;
}

// The mean of the 4 x 4 pixels around (x, y).
glm::vec3 block_mean(const image::Image& img, uint32_t x, uint32_t y) {
  glm::vec3 sum(0.0f);
  for (uint32_t j = y - 2; j < y + 2; ++j)
    for (uint32_t i = x - 2; i < x + 2; ++i)
      for (int c = 0; c < 3; ++c) sum[c] += img.rgba[4 * (size_t(j) * kSize + i) + size_t(c)];
  return sum / 16.0f;
}

void expect_near(glm::vec3 got, glm::vec3 want, const char* where) {
  for (int c = 0; c < 3; ++c) EXPECT_NEAR(got[c], want[c], 0.03f) << where << " channel " << c;
}

class Textures : public GpuTest {};

TEST_F(Textures, BaseColourTextureIsUprightAndDecodedFromSrgb) {
  scene::Scene s;
  s.name = "textured quad";
  // Top row red, green; bottom row blue, grey 128 (sRGB: 0.2159 linear).
  const image::Rgba8Image img{2, 2, {rgba(255, 0, 0), rgba(0, 255, 0), rgba(0, 0, 255), rgba(128, 128, 128)}};
  scene::Material m = lambert(glm::vec3(1.0f));
  m.base_color_texture.texture = add_texture(s, img, scene::ColorSpace::kSrgb);
  s.materials.push_back(m);
  add_instance(s, uv_quad(1.0f, 0.0f, 0));
  frame_quad(s);
  s.validate();
  const image::Image out = render(s);
  expect_near(block_mean(out, 12, 12), {1, 0, 0}, "top left");
  expect_near(block_mean(out, 20, 12), {0, 1, 0}, "top right");
  expect_near(block_mean(out, 12, 20), {0, 0, 1}, "bottom left");
  expect_near(block_mean(out, 20, 20), glm::vec3(scene::srgb_to_linear(128)), "bottom right");
  expect_near(block_mean(out, 3, 3), glm::vec3(1.0f), "environment");
}

TEST_F(Textures, AlphaMaskShowsWhatLiesBehindItsTransparentTexels) {
  scene::Scene s;
  s.name = "alpha-masked quad";
  // Left column transparent (alpha 0), right column opaque; all texels white.
  const image::Rgba8Image img{2, 2, {rgba(255, 255, 255, 0), rgba(255, 255, 255), rgba(255, 255, 255, 0), rgba(255, 255, 255)}};
  scene::Material front = lambert({0.9f, 0.1f, 0.1f});
  front.base_color_texture.texture = add_texture(s, img, scene::ColorSpace::kSrgb);
  front.alpha_mode = scene::AlphaMode::kMask;
  front.alpha_cutoff = 0.5f;
  s.materials.push_back(front);
  s.materials.push_back(lambert({0.1f, 0.1f, 0.9f}));
  add_instance(s, uv_quad(1.0f, 0.0f, 0));
  add_instance(s, uv_quad(8.0f, -0.5f, 1));  // behind, filling the view
  frame_quad(s);
  s.validate();
  const image::Image out = render(s);
  // Through the transparent half: the blue back quad (lit by the environment past the front quad's
  // opaque half); the opaque half: the red front quad, which sees only the environment.
  const glm::vec3 left = block_mean(out, 12, 16);
  const glm::vec3 right = block_mean(out, 20, 16);
  EXPECT_GT(left.b, 3.0f * left.r) << "the transparent half shows the blue quad behind";
  EXPECT_GT(right.r, 3.0f * right.b) << "the opaque half is the red quad";
  EXPECT_NEAR(right.r, 0.9f, 0.05f);
}

}  // namespace
}  // namespace strata::test
