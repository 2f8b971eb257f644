// Deforming meshes on the device (docs/ARCHITECTURE.md, "Deforming meshes"): the pass `deform`
// writes each deforming instance's vertex copy of the slot being recorded as the host reference
// (scene/deform.h) computes it, and with history the other slot keeps the previous frame's.
#include <algorithm>
#include <cmath>
#include <string>

#include "gpu/gpu_context.h"
#include "include/scene_data.h"
#include "render/scene_gpu.h"
#include "scene/deform.h"
#include "scene/scene_io.h"

namespace strata::test {
namespace {

class Deform : public GpuTest {};

// The largest distance between the device's copy of instance i in `slot` and the host's deformation
// of `frame`, over positions, relative to the mesh's size; and the largest normal difference.
struct Difference {
  double position = 0.0;
  double normal = 0.0;
};

Difference compare(const render::GpuScene& gs, const std::vector<gpu::GpuVertex>& device, size_t i, int slot,
                   const scene::FrameState& frame) {
  const scene::Scene& s = gs.scene();
  const scene::Instance& inst = s.instances[i];
  std::vector<scene::SkinningMatrix> skinning;
  if (inst.skin >= 0) skinning = scene::skinning_matrices(s.skins[size_t(inst.skin)], frame.transforms[i], frame.joints[i]);
  uint32_t v0 = gs.deformation()->vertex_base(i, slot);
  Difference d;
  for (const scene::Primitive& p : s.meshes[inst.lod_meshes.front()].primitives) {
    const scene::DeformedVertices host = scene::deform_primitive(p, skinning, frame.morph_weights[i]);
    float extent = 0.0f;
    for (const glm::vec3& x : host.positions) extent = std::max(extent, glm::length(x));
    for (size_t v = 0; v < host.positions.size(); ++v) {
      const gpu::GpuVertex& g = device.at(v0 + v);
      d.position = std::max(d.position, double(glm::length(glm::vec3(g.position_u) - host.positions[v]) / std::max(extent, 1e-6f)));
      d.normal = std::max(d.normal, double(glm::length(glm::vec3(g.normal_v) - host.normals[v])));
      EXPECT_EQ(g.position_u.w, p.uvs[v].x) << "the copy keeps its texCoords";
    }
    v0 += uint32_t(p.positions.size());
  }
  return d;
}

// The float tolerance: the device and the host compute the same sums in float, in the same order;
// fused multiply-adds and the 4 x 4 products' rounding differ by a few ulps of the mesh's extent.
constexpr double kPositionTolerance = 1e-5;
constexpr double kNormalTolerance = 1e-4;

void check_frames(const scene::Scene& s, bool history, std::initializer_list<uint32_t> frames) {
  render::GpuScene gs(gpu_context(), s, history);
  ASSERT_NE(gs.deformation(), nullptr);
  scene::FrameState previous;
  bool have_previous = false;
  for (uint32_t f : frames) {
    const scene::FrameState frame = s.frame_state(f);
    gpu_context().submit_and_wait([&](VkCommandBuffer cmd) { gs.record_update(cmd, frame); });
    const auto device = gs.vertices().download_as<gpu::GpuVertex>(gs.vertices().size() / sizeof(gpu::GpuVertex));
    for (size_t i = 0; i < s.instances.size(); ++i) {
      if (!s.instances[i].deforms()) continue;
      const std::string where = s.name + " instance " + std::to_string(i) + " frame " + std::to_string(f);
      const Difference now = compare(gs, device, i, gs.parity(), frame);
      EXPECT_LT(now.position, kPositionTolerance) << where;
      EXPECT_LT(now.normal, kNormalTolerance) << where;
      if (history && have_previous) {
        const Difference before = compare(gs, device, i, 1 - gs.parity(), previous);
        EXPECT_LT(before.position, kPositionTolerance) << where << ": the previous slot lost the previous frame";
      }
    }
    previous = frame;
    have_previous = true;
  }
}

TEST_F(Deform, DeviceMatchesHostOnTheBuiltInScene) {
  const scene::Scene s = scene::load_scene("characters");
  check_frames(s, false, {0, 17, 61});
  check_frames(s, true, {0, 17, 18, 61});
}

// Debian's assimp-testmodels (installed by deploy/install-deps.sh): a skinned strip whose joint
// turns, and a cube whose two morph targets animate.
TEST_F(Deform, DeviceMatchesHostOnTheCorpus) {
  const std::string corpus = "/usr/share/assimp/models/glTF2/";
  const scene::Scene skin = scene::load_scene(corpus + "simple_skin/simple_skin.gltf");
  check_frames(skin, true, {0, 15, 30});
  const scene::Scene morph = scene::load_scene(corpus + "glTF-Sample-Models/AnimatedMorphCube-glTF/AnimatedMorphCube.gltf");
  check_frames(morph, true, {0, 20, 40});
}

// The deformation moves the vertices: frames 0 and 17 of the flag and the blob differ by far more
// than the tolerance (the comparison above could not pass with rest vertices).
TEST_F(Deform, FramesDiffer) {
  const scene::Scene s = scene::load_scene("characters");
  render::GpuScene gs(gpu_context(), s, false);
  std::vector<gpu::GpuVertex> a, b;
  for (uint32_t f : {0u, 17u}) {
    gpu_context().submit_and_wait([&](VkCommandBuffer cmd) { gs.record_update(cmd, s.frame_state(f)); });
    (f == 0 ? a : b) = gs.vertices().download_as<gpu::GpuVertex>(gs.vertices().size() / sizeof(gpu::GpuVertex));
  }
  for (size_t i = 0; i < s.instances.size(); ++i) {
    if (!s.instances[i].deforms()) continue;
    const uint32_t v0 = gs.deformation()->vertex_base(i, 0);
    float moved = 0.0f;
    for (size_t v = v0; v < v0 + 100; ++v) moved = std::max(moved, glm::length(glm::vec3(a[v].position_u - b[v].position_u)));
    EXPECT_GT(moved, 0.01f) << s.instances[i].name << " did not move between frames 0 and 17";
  }
}

}  // namespace
}  // namespace strata::test
