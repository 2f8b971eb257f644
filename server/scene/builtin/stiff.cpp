// stiff: extreme inputs for the numerics suite. Everything (camera included) sits 1e5 m from the
// origin, translated by (1e5, 0, 1e5): meshes stay small in object space and the offset lives in
// the instance transforms, where float spacing is ~8 mm. A 1 mm x 1 mm emitter of radiance 1e6
// hangs 1 m above a near-specular floor (metallic 1, roughness 0.02) beside a 100 m x 100 m
// ceiling emitter of radiance 0.01 (a 1e8 dynamic range); a sphere, a box and a cylinder are
// matte. No environment light.
// Animation: the camera sways 0.6 m sideways (about 75 float steps at this distance).
#include <utility>

#include <glm/gtc/matrix_transform.hpp>

#include "scene/builtin/builtins.h"
#include "scene/builtin/common.h"
#include "scene/builtin/shapes.h"

namespace strata::scene::builtin {
namespace {

const glm::vec3 kOffset(1e5f, 0.0f, 1e5f);

glm::mat4 placed(const glm::vec3& local) {
  return glm::translate(glm::mat4(1.0f), kOffset + local);
}

}  // namespace

Scene make_stiff() {
  SceneBuilder b("stiff");
  const uint32_t mirror = b.material("near_specular", {0.9f, 0.9f, 0.9f}, 1.0f, 0.02f);
  const uint32_t matte = b.material("matte", {0.6f, 0.6f, 0.6f});
  const uint32_t orange = b.material("orange", {0.8f, 0.4f, 0.1f});
  const uint32_t tiny = b.emitter("tiny_emitter", glm::vec3(1e6f));
  const uint32_t huge = b.emitter("huge_emitter", glm::vec3(0.01f));
  const glm::vec3 down(0.0f, -1.0f, 0.0f);

  b.instance("floor", b.mesh("floor", {quad({-20, 0, 20}, {40, 0, 0}, {0, 0, -40}, mirror)}),
             placed({}));
  b.instance("tiny_emitter", b.mesh("tiny_emitter", {facing_quad({}, down, 1e-3f, 1e-3f, tiny)}),
             placed({0.5f, 1.0f, 0.0f}));
  b.instance("huge_emitter", b.mesh("huge_emitter", {facing_quad({}, down, 100.0f, 100.0f, huge)}),
             placed({0.0f, 40.0f, 0.0f}));
  b.instance("sphere", b.mesh("sphere", {uv_sphere(0.4f, 24, 16, matte)}),
             placed({-0.8f, 0.4f, 0.0f}));
  b.instance("box", b.mesh("box", {box(glm::vec3(0.3f), orange)}), placed({0.8f, 0.3f, -0.5f}));
  b.instance("cylinder", b.mesh("cylinder", {cylinder(0.25f, 0.8f, 32, matte)}),
             placed({0.0f, 0.0f, -1.2f}));

  const glm::vec3 target = kOffset + glm::vec3(0.0f, 0.5f, 0.0f);
  auto sway = [&](uint32_t f) {
    const float x = -0.3f + 0.6f * static_cast<float>(f) / static_cast<float>(kFrameCount - 1);
    return std::pair{kOffset + glm::vec3(x, 1.5f, 4.0f), target};
  };
  b.camera(sway(0).first, target, 0.7f);
  b.camera_path(sway);
  return b.finish();
}

}  // namespace strata::scene::builtin
