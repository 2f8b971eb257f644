// The reference estimator against cases with known answers: the furnace, darkness, open sky.
#include <array>
#include <chrono>
#include <cmath>
#include <cstdio>

#include <gtest/gtest.h>

#include "support/cpu_tracer.h"

namespace strata::test {
namespace {

using scene::FrameState;
using scene::Scene;

// The cube [-1,1]^3 as six quads (two triangles each). With `inward`, every quad winds
// counter-clockwise seen from inside, so front faces (and emission) point into the box.
Scene box_scene(const scene::Material& material, bool inward) {
  Scene s;
  s.materials.push_back(material);
  scene::Mesh mesh{"box", {}};
  for (int axis = 0; axis < 3; ++axis) {
    for (float side : {-1.0f, 1.0f}) {
      const int b = (axis + 1) % 3, c = (axis + 2) % 3;
      glm::vec3 normal(0.0f);
      normal[axis] = inward ? -side : side;
      scene::Primitive p;
      const std::array<glm::vec2, 4> corners = {{{-1, -1}, {1, -1}, {1, 1}, {-1, 1}}};
      for (const glm::vec2& corner : corners) {
        glm::vec3 v(0.0f);
        v[axis] = side;
        v[b] = corner.x;
        v[c] = corner.y;
        p.positions.push_back(v);
        p.normals.push_back(normal);
        p.uvs.push_back(corner);
      }
      const glm::vec3 ng = glm::cross(p.positions[1] - p.positions[0], p.positions[2] - p.positions[0]);
      p.indices = glm::dot(ng, normal) > 0.0f ? std::vector<uint32_t>{0, 1, 2, 0, 2, 3}
                                              : std::vector<uint32_t>{0, 2, 1, 0, 3, 2};
      mesh.primitives.push_back(p);
    }
  }
  s.meshes.push_back(mesh);
  s.instances.push_back({"box", {0}, glm::mat4(1.0f), 0});
  // Off-centre and turned, so that no symmetry of the set-up hides a camera bug.
  s.camera.position = {0.1f, -0.2f, 0.3f};
  s.camera.orientation = glm::angleAxis(0.7f, glm::normalize(glm::vec3(0.3f, 1.0f, 0.2f)));
  s.camera.yfov = 1.0f;
  return s;
}

FrameState frame_of(const Scene& s) {
  return FrameState{s.camera, {s.instances[0].transform}, {s.instances[0].lod}};
}

scene::Material lambert(float albedo, float emission, bool double_sided = false) {
  scene::Material m;
  m.base_color = glm::vec3(albedo);
  m.emission = glm::vec3(emission);
  m.double_sided = double_sided;
  return m;
}

void expect_within_4_sigma(const MeanEstimate& e, double expected) {
  for (int c = 0; c < 3; ++c) {
    EXPECT_GT(e.std_error[c], 0.0);
    EXPECT_LT(e.std_error[c], 0.01 * expected);
    EXPECT_LE(std::abs(e.mean[c] - expected), 4.0 * e.std_error[c])
        << "channel " << c << ": " << e.mean[c] << " +- " << e.std_error[c];
  }
}

TEST(CpuTracerEstimate, FurnaceBoxConvergesToEmissionOverOneMinusAlbedo) {
  // Every path stays in the box, so L = Le (1 + a + a^2 + ...) = Le / (1 - a) = 2 exactly.
  const Scene s = box_scene(lambert(0.5f, 1.0f), true);
  const auto start = std::chrono::steady_clock::now();
  const MeanEstimate e = estimate_image_mean(s, frame_of(s), 64, 48, 16, 1234);
  const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  RecordProperty("furnace_seconds", std::to_string(seconds));
  std::printf("furnace: mean %.5f +- %.5f over %llu paths in %.3f s\n", e.mean.x, e.std_error.x,
              static_cast<unsigned long long>(e.paths), seconds);
  EXPECT_EQ(e.paths, 64u * 48u * 16u);
  expect_within_4_sigma(e, 2.0);
}

TEST(CpuTracerEstimate, DoubleSidedEmitsFromBackFaces) {
  // Outward-facing walls: seen from inside only back faces, which emit only when double-sided.
  const Scene dark = box_scene(lambert(0.5f, 1.0f), false);
  const MeanEstimate none = estimate_image_mean(dark, frame_of(dark), 8, 8, 4, 7);
  EXPECT_EQ(none.mean, glm::dvec3(0.0));
  const Scene lit = box_scene(lambert(0.5f, 1.0f, true), false);
  expect_within_4_sigma(estimate_image_mean(lit, frame_of(lit), 32, 32, 16, 7), 2.0);
}

TEST(CpuTracerEstimate, NoEmittersGiveExactlyZero) {
  const Scene s = box_scene(lambert(0.9f, 0.0f), true);
  const MeanEstimate e = estimate_image_mean(s, frame_of(s), 16, 8, 4, 99);
  EXPECT_EQ(e.mean, glm::dvec3(0.0));
  EXPECT_EQ(e.std_error, glm::dvec3(0.0));
  EXPECT_EQ(e.paths, 16u * 8u * 4u);
}

TEST(CpuTracerEstimate, EnvironmentOnlyGivesTheEnvironmentExactly) {
  Scene s;
  s.environment.radiance = {0.3f, 1.7f, 12.5f};
  const FrameState f{s.camera, {}, {}};
  const MeanEstimate e = estimate_image_mean(s, f, 13, 7, 3, 5);
  EXPECT_EQ(e.mean, glm::dvec3(s.environment.radiance));
  EXPECT_EQ(e.std_error, glm::dvec3(0.0));
}

TEST(CpuTracerEstimate, DeterministicPerSeed) {
  const Scene s = box_scene(lambert(0.5f, 1.0f), true);
  const MeanEstimate a = estimate_image_mean(s, frame_of(s), 12, 10, 2, 42);
  const MeanEstimate b = estimate_image_mean(s, frame_of(s), 12, 10, 2, 42);
  const MeanEstimate c = estimate_image_mean(s, frame_of(s), 12, 10, 2, 43);
  EXPECT_EQ(a.mean, b.mean);
  EXPECT_EQ(a.std_error, b.std_error);
  EXPECT_NE(a.mean, c.mean);
}

TEST(CpuTracerEstimate, MaxDepthCutsPaths) {
  // With one vertex per path only the directly seen emission counts, and it is exactly Le.
  const Scene s = box_scene(lambert(0.5f, 1.0f), true);
  const MeanEstimate e = estimate_image_mean(s, frame_of(s), 8, 8, 2, 3, 1);
  EXPECT_EQ(e.mean, glm::dvec3(1.0));
  EXPECT_EQ(e.std_error, glm::dvec3(0.0));
}

TEST(CpuTracerEstimate, RejectsWhatItCannotRender) {
  Scene s = box_scene(lambert(0.5f, 1.0f), true);
  EXPECT_THROW(estimate_image_mean(s, frame_of(s), 0, 8, 1, 1), std::invalid_argument);
  EXPECT_THROW(estimate_image_mean(s, frame_of(s), 8, 8, 0, 1), std::invalid_argument);
  s.camera.aperture = 0.1f;
  EXPECT_THROW(estimate_image_mean(s, frame_of(s), 8, 8, 1, 1), std::invalid_argument);
  s.camera.aperture = 0.0f;
  s.materials[0].metallic = 1.0f;
  EXPECT_THROW(estimate_image_mean(s, frame_of(s), 8, 8, 1, 1), std::invalid_argument);
}

}  // namespace
}  // namespace strata::test
