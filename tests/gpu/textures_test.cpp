// Textures and alpha-tested materials on the device: a 2 x 2 base colour texture on a quad facing
// the camera, lit by a constant white environment (Lambert without a specular lobe, paths of at most
// two segments: every pixel's expectation is its texel's linear colour), read back per quadrant for
// the texture's orientation (UV (0, 0) is the image's top-left corner) and its sRGB decoding; and an
// alpha-masked quad in front of another, whose transparent half shows what lies behind it.
#include <algorithm>

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
  scene::Sampler nearest;
  nearest.mag_filter = scene::TextureFilter::kNearest;
  return scene::add_texture(s.textures, image, space, "known", nearest);
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

// The three wrap modes on a quad filling the view whose u runs over [-1, 2] (v over [0, 1]): a 2 x 1
// texture, red then green, with nearest magnification, read at the middle of each sixth of the quad.
TEST_F(Textures, WrapModesRepeatMirrorAndClampOutsideTheUnitSquare) {
  struct Mode {
    scene::TextureWrap wrap;
    const char* name;
    const char* texels;  // per sixth of u in [-1, 2]: R red, G green
  };
  // Sixths centred at u = -0.75, -0.25, 0.25, 0.75, 1.25, 1.75.
  for (const Mode mode : {Mode{scene::TextureWrap::kRepeat, "repeat", "RGRGRG"},
                          Mode{scene::TextureWrap::kMirroredRepeat, "mirrored repeat", "GRRGGR"},
                          Mode{scene::TextureWrap::kClampToEdge, "clamp to edge", "RRRGGG"}}) {
    SCOPED_TRACE(mode.name);
    scene::Scene s;
    s.name = "wrapped quad";
    scene::Material m = lambert(glm::vec3(1.0f));
    m.base_color_texture.texture = add_texture(s, image::Rgba8Image{2, 1, {rgba(255, 0, 0), rgba(0, 255, 0)}}, scene::ColorSpace::kLinear);
    s.textures.textures.back().sampler.wrap_u = mode.wrap;
    s.materials.push_back(m);
    scene::Mesh quad = uv_quad(2.0f, 0.0f, 0);  // fills the view
    quad.primitives[0].uvs = {{-1, 1}, {2, 1}, {2, 0}, {-1, 0}};
    add_instance(s, quad);
    frame_quad(s);
    s.validate();
    const image::Image out = render(s);
    for (uint32_t k = 0; k < 6; ++k) {
      const uint32_t x = uint32_t((float(k) + 0.5f) * float(kSize) / 6.0f);
      const glm::vec3 c = block_mean(out, std::clamp(x, 2u, kSize - 2), 16);
      const bool red = mode.texels[k] == 'R';
      EXPECT_GT(red ? c.r : c.g, 0.8f) << "sixth " << k;
      EXPECT_LT(red ? c.g : c.r, 0.2f) << "sixth " << k;
    }
  }
}

// An emitter whose emissive texture is 2 x 2 texels with nearest magnification is the same light as
// four untextured quads, one per texel, each emitting its texel: a Lambert floor lit by either (pt:
// next-event estimation selecting the textured triangles by their integrated texture, the light
// sample's radiance the texel, MIS against BSDF hits that read the texel) has the same expectation.
scene::Scene lit_floor(bool textured) {
  scene::Scene s;
  s.name = textured ? "textured emitter" : "four emitters";
  s.materials.push_back(lambert(glm::vec3(0.8f)));
  add_instance(s, uv_quad(2.0f, 0.0f, 0));  // the floor, facing the camera
  // Texels: top row (v = 0) bright red, dim; bottom row dim, bright blue (linear, as stored).
  const glm::vec3 texel[4] = {{4, 0.4f, 0.4f}, {0.2f, 0.2f, 0.2f}, {0.2f, 0.2f, 0.2f}, {0.4f, 0.4f, 4}};
  // The light: a 1 x 1 m quad 0.5 m in front of the floor, facing it, just right of the view.
  const glm::vec3 o(1.8f, -0.5f, 0.5f);
  auto light_quad = [&](glm::vec2 lo, glm::vec2 hi, uint32_t material, bool uvs) {
    scene::Primitive p;
    // Facing -Z: counter-clockwise seen from below.
    p.positions = {o + glm::vec3(lo.x, lo.y, 0), o + glm::vec3(lo.x, hi.y, 0), o + glm::vec3(hi.x, hi.y, 0), o + glm::vec3(hi.x, lo.y, 0)};
    p.normals.assign(4, glm::vec3(0, 0, -1));
    // UV (0, 0) at the quad's top-left (x low, y high), as uv_quad maps it.
    p.uvs = uvs ? std::vector<glm::vec2>{{0, 1}, {0, 0}, {1, 0}, {1, 1}} : std::vector<glm::vec2>(4, glm::vec2(0));
    p.indices = {0, 1, 2, 0, 2, 3};
    p.material = material;
    scene::Mesh m;
    m.primitives.push_back(p);
    add_instance(s, m);
  };
  if (textured) {
    image::Rgba8Image img{2, 2, {}};
    for (const glm::vec3& t : texel) img.texels.push_back(rgba(uint8_t(t.r * 63.75f), uint8_t(t.g * 63.75f), uint8_t(t.b * 63.75f)));
    scene::Material e = lambert(glm::vec3(0.0f));
    e.emission = glm::vec3(4.0f);  // x the texel (linear), so texel byte b emits 4 b / 255
    e.emissive_texture.texture = add_texture(s, img, scene::ColorSpace::kLinear);
    s.materials.push_back(e);
    light_quad({0, 0}, {1, 1}, 1, true);
  } else {
    for (int k = 0; k < 4; ++k) {
      scene::Material e = lambert(glm::vec3(0.0f));
      const glm::vec3 t = texel[k];
      e.emission = 4.0f * glm::vec3(float(uint8_t(t.r * 63.75f)), float(uint8_t(t.g * 63.75f)), float(uint8_t(t.b * 63.75f))) / 255.0f;
      s.materials.push_back(e);
      const float x0 = k % 2 == 0 ? 0.0f : 0.5f, y0 = k / 2 == 0 ? 0.5f : 0.0f;  // texel row 0 is the top (high y)
      light_quad({x0, y0}, {x0 + 0.5f, y0 + 0.5f}, uint32_t(s.materials.size() - 1), false);
    }
  }
  frame_quad(s);
  s.environment.radiance = glm::vec3(0.0f);
  s.validate();
  return s;
}

TEST_F(Textures, TexturedEmitterLightsLikeOneEmitterPerTexel) {
  render::RenderSettings rs;
  rs.width = kSize;
  rs.height = kSize;
  rs.spp = 256;
  rs.max_depth = 2;
  rs.seed = 9;
  const scene::Scene textured = lit_floor(true), split = lit_floor(false);
  const image::Image a = render::Renderer(gpu_context(), textured, rs).render(textured.frame_state(0), 0).image;
  const image::Image b = render::Renderer(gpu_context(), split, rs).render(split.frame_state(0), 0).image;
  // Per 8 x 8 block and channel: the red light's corner is red, the blue one's blue.
  for (uint32_t by = 0; by < kSize; by += 8) {
    for (uint32_t bx = 0; bx < kSize; bx += 8) {
      glm::dvec3 sa(0.0), sb(0.0);
      for (uint32_t y = by; y < by + 8; ++y)
        for (uint32_t x = bx; x < bx + 8; ++x)
          for (int c = 0; c < 3; ++c) {
            sa[c] += a.rgba[4 * (size_t(y) * kSize + x) + size_t(c)];
            sb[c] += b.rgba[4 * (size_t(y) * kSize + x) + size_t(c)];
          }
      for (int c = 0; c < 3; ++c) EXPECT_NEAR(sa[c], sb[c], 0.04 * sb[c] + 0.02) << "block " << bx << ", " << by << " channel " << c;
    }
  }
}

}  // namespace
}  // namespace strata::test
