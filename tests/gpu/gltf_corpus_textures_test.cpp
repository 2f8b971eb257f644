// The textured files of the assimp glTF 2.0 corpus (Debian's assimp-testmodels, under
// /usr/share/assimp/models/glTF2; tests/unit/gltf_conformance_test.cpp loads every file) show their
// base colour texture on the device: rendered as loaded, the pixels of the textured surfaces vary
// clearly more than in a render of the same file with its textures removed. Under a constant white
// environment with paths of at most two segments, an untextured convex object's pixels are its
// factor times the environment up to noise and shading; the texture's texels add their variation.
// The variance is taken within each textured material's pixels, which a third render labels (each
// material emitting a value of its own), and pooled over the materials. Skipped when the package is not installed.
#include <algorithm>
#include <cmath>
#include <filesystem>
#include <map>
#include <string>
#include <vector>

#include <glm/glm.hpp>

#include "gpu/gpu_context.h"
#include "render/renderer.h"
#include "scene/scene_io.h"

namespace strata::test {
namespace {

namespace fs = std::filesystem;

const fs::path kCorpus = "/usr/share/assimp/models/glTF2";
constexpr uint32_t kSize = 48;

// The files whose level 0 of some base colour texture is not one colour, and that load.
std::vector<fs::path> textured_files() {
  std::vector<fs::path> files;
  std::error_code ec;
  for (fs::recursive_directory_iterator it(kCorpus, ec), end; !ec && it != end; it.increment(ec)) {
    const std::string ext = it->path().extension().string();
    if (!it->is_regular_file() || (ext != ".gltf" && ext != ".glb")) continue;
    try {
      const scene::Scene s = scene::load_gltf_file(it->path());
      const bool textured = std::any_of(s.materials.begin(), s.materials.end(), [&](const scene::Material& m) {
        if (m.base_color_texture.texture < 0) return false;
        const auto& image = s.textures.images[s.textures.textures[size_t(m.base_color_texture.texture)].image];
        const scene::MipLevel& top = s.textures.levels[image.first_level];
        const auto first = s.textures.texels.begin() + std::ptrdiff_t(top.offset);
        return std::any_of(first, first + std::ptrdiff_t(top.width) * top.height, [&](uint32_t t) { return t != *first; });
      });
      if (textured) files.push_back(it->path());
    } catch (const scene::SceneError&) {
      // refused files are the conformance test's
    }
  }
  std::sort(files.begin(), files.end());
  return files;
}

// Textured files whose texture this test cannot see at kSize, with why; they must still render.
const std::map<std::string, std::string>& unseen() {
  static const std::map<std::string, std::string> table = {
      {"ClearCoat-glTF/ClearCoatTest.gltf", "the textured surfaces are thin text labels, 18 pixels"},
      {"issue_3269/texcoord_crash.gltf",
       "each quad reads a mostly white corner of a label image (small text, white under the factor); one reads "
       "TEXCOORD_0, which its primitive lacks (zeros: one texel)"},
  };
  return table;
}

image::Image render(scene::Scene s) {
  s.environment = {};
  s.environment.radiance = glm::vec3(1.0f);
  s.validate();
  render::RenderSettings rs;
  rs.width = kSize;
  rs.height = kSize;
  rs.spp = 32;
  rs.max_depth = 2;
  rs.seed = 9;
  render::Renderer renderer(gpu_context(), s, rs);
  return renderer.render(s.frame_state(0), 0).image;
}

float luminance(const image::Image& img, size_t pixel) {
  return 0.2126f * img.rgba[4 * pixel] + 0.7152f * img.rgba[4 * pixel + 1] + 0.0722f * img.rgba[4 * pixel + 2];
}

// The luminance variance within each group of pixels (label >= 0), pooled over the groups: the
// variation inside each textured material, not between materials of different factors.
double pooled_variance(const image::Image& img, const std::vector<int>& label, int groups) {
  std::vector<double> sum(size_t(groups), 0.0);
  std::vector<double> sum2(size_t(groups), 0.0);
  std::vector<size_t> n(size_t(groups), 0);
  for (size_t i = 0; i < label.size(); ++i) {
    if (label[i] < 0) continue;
    const double l = luminance(img, i);
    sum[size_t(label[i])] += l;
    sum2[size_t(label[i])] += l * l;
    ++n[size_t(label[i])];
  }
  double within = 0.0;
  size_t total = 0;
  for (size_t k = 0; k < size_t(groups); ++k) {
    if (n[k] < 2) continue;
    const double mean = sum[k] / double(n[k]);
    within += std::max(0.0, sum2[k] - double(n[k]) * mean * mean);
    total += n[k];
  }
  return total > 0 ? within / double(total) : 0.0;
}

class GltfCorpusTextures : public GpuTest {
 protected:
  void SetUp() override {
    GpuTest::SetUp();
    if (!fs::is_directory(kCorpus)) GTEST_SKIP() << kCorpus << " is missing (apt-get install assimp-testmodels)";
  }
};

TEST_F(GltfCorpusTextures, TexturedFilesShowTheirBaseColourTexture) {
  const std::vector<fs::path> files = textured_files();
  // BoxTextured in three encodings, boxTexcoords, ClearCoatTest, TextureTransformTest at least.
  EXPECT_GE(files.size(), 6u);
  for (const auto& [name, why] : unseen())
    EXPECT_NE(std::find(files.begin(), files.end(), kCorpus / name), files.end()) << name << " is no longer textured";
  for (const fs::path& file : files) {
    const std::string name = fs::relative(file, kCorpus).string();
    SCOPED_TRACE(name);
    const scene::Scene loaded = scene::load_gltf_file(file);
    if (unseen().count(name) != 0) {
      (void)render(loaded);
      continue;
    }
    scene::Scene untextured = loaded;
    scene::Scene labels = loaded;
    for (scene::Material& m : untextured.materials) {
      m.base_color_texture = {};
      m.metallic_roughness_texture = {};
      m.normal_texture = {};
      m.emissive_texture = {};
    }
    // The label render: the k-th of n textured materials emits (k + 1) / (n + 1) x 0.9 and reflects
    // nothing, the others emit 4; a pixel whose luminance is within a quarter step of a textured
    // material's shows that material alone (edge pixels mixing two surfaces are left out).
    int groups = 0;
    std::vector<int> group_of(loaded.materials.size(), -1);
    for (size_t m = 0; m < loaded.materials.size(); ++m)
      if (loaded.materials[m].base_color_texture.texture >= 0) group_of[m] = groups++;
    const float step = 0.9f / float(groups + 1);
    for (size_t m = 0; m < labels.materials.size(); ++m) {
      labels.materials[m] = scene::Material{};
      labels.materials[m].base_color = glm::vec3(0.0f);
      labels.materials[m].specular = 0.0f;
      labels.materials[m].double_sided = true;
      labels.materials[m].emission = glm::vec3(group_of[m] >= 0 ? step * float(group_of[m] + 1) : 4.0f);
    }
    const image::Image shape = render(labels);
    std::vector<int> label(size_t(kSize) * kSize, -1);
    size_t covered = 0;
    for (size_t i = 0; i < label.size(); ++i) {
      const float k = luminance(shape, i) / step - 1.0f;
      if (std::abs(k - std::round(k)) < 0.25f && std::round(k) >= 0.0f && std::round(k) < float(groups)) {
        label[i] = int(std::round(k));
        ++covered;
      }
    }
    if (covered < 16) {
      ADD_FAILURE() << "the framing camera sees " << covered << " pixels of textured surfaces";
      continue;
    }
    const double textured_var = pooled_variance(render(loaded), label, groups);
    const double untextured_var = pooled_variance(render(untextured), label, groups);
    RecordProperty(name, std::to_string(textured_var) + " / " + std::to_string(untextured_var));
    EXPECT_GT(textured_var, 4.0 * untextured_var + 1e-3)
        << "luminance variance over " << covered << " pixels: textured " << textured_var << ", untextured " << untextured_var;
  }
}

}  // namespace
}  // namespace strata::test
