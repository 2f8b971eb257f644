// The reference tracer's geometry: world-space triangles, closest hits, barycentrics and faces.
#include <glm/gtc/matrix_transform.hpp>
#include <gtest/gtest.h>

#include "support/cpu_tracer.h"

namespace strata::test {
namespace {

using scene::FrameState;
using scene::Scene;

// One triangle in the z = 0 plane, counter-clockwise seen from +z (front normal +z).
scene::Primitive unit_triangle(float x_offset = 0.0f) {
  scene::Primitive p;
  p.positions = {{x_offset, 0, 0}, {x_offset + 1, 0, 0}, {x_offset, 1, 0}};
  p.normals = {{0, 0, 1}, {0, 0, 1}, {0, 0, 1}};
  p.uvs = {{0, 0}, {1, 0}, {0, 1}};
  p.indices = {0, 1, 2};
  return p;
}

// Instances of mesh 0 (one unit triangle) at the given transforms.
Scene triangle_scene(const std::vector<glm::mat4>& transforms) {
  Scene s;
  s.materials.push_back({});
  s.meshes.push_back({"tri", {unit_triangle()}});
  for (const glm::mat4& t : transforms) s.instances.push_back({"i", {0}, t, 0});
  return s;
}

FrameState frame_of(const Scene& s) {
  FrameState f{s.camera, {}, {}};
  for (const scene::Instance& i : s.instances) {
    f.transforms.push_back(i.transform);
    f.lods.push_back(i.lod);
  }
  return f;
}

glm::mat4 translate(float x, float y, float z) { return glm::translate(glm::mat4(1.0f), {x, y, z}); }

CpuRay down_z(double x, double y) { return CpuRay{{x, y, 1.0}, {0.0, 0.0, -1.0}}; }

TEST(CpuTracerIntersect, HitReportsDistanceBarycentricsAndNormal) {
  const Scene s = triangle_scene({translate(0, 0, -2)});
  const CpuScene cpu = build_cpu_scene(s, frame_of(s));
  const auto hit = intersect(cpu, down_z(0.25, 0.125));
  ASSERT_TRUE(hit);
  EXPECT_DOUBLE_EQ(hit->t, 3.0);
  EXPECT_DOUBLE_EQ(hit->u, 0.25);  // weight of p1 = (1, 0)
  EXPECT_DOUBLE_EQ(hit->v, 0.125);
  EXPECT_EQ(hit->geometric_normal, glm::dvec3(0, 0, 1));
  EXPECT_EQ(hit->instance, 0u);
  EXPECT_EQ(hit->primitive, 0u);
  EXPECT_EQ(hit->triangle, 0u);
}

TEST(CpuTracerIntersect, Misses) {
  const Scene s = triangle_scene({glm::mat4(1.0f)});
  const CpuScene cpu = build_cpu_scene(s, frame_of(s));
  EXPECT_FALSE(intersect(cpu, down_z(0.75, 0.75)));                          // outside the edge
  EXPECT_FALSE(intersect(cpu, CpuRay{{0.2, 0.2, 1.0}, {0.0, 0.0, 1.0}}));    // pointing away
  EXPECT_FALSE(intersect(cpu, CpuRay{{0.2, 0.2, 1.0}, {1.0, 0.0, 0.0}}));    // parallel
  EXPECT_FALSE(intersect(cpu, CpuRay{{0.2, 0.2, 1.0}, {0, 0, -1}, 0.0, 0.5}));  // beyond t_max
  EXPECT_FALSE(intersect(CpuScene{}, down_z(0.2, 0.2)));
}

TEST(CpuTracerIntersect, ClosestOfTwo) {
  // The far instance comes first, so a first-hit intersector would get it wrong.
  const Scene s = triangle_scene({translate(0, 0, -5), translate(0, 0, -2)});
  const CpuScene cpu = build_cpu_scene(s, frame_of(s));
  const auto hit = intersect(cpu, down_z(0.2, 0.2));
  ASSERT_TRUE(hit);
  EXPECT_EQ(hit->instance, 1u);
  EXPECT_DOUBLE_EQ(hit->t, 3.0);
  // t_min past the near one, or ignoring it, finds the far one.
  const auto far = intersect(cpu, CpuRay{{0.2, 0.2, 1.0}, {0, 0, -1}, 3.5});
  ASSERT_TRUE(far);
  EXPECT_EQ(far->instance, 0u);
  CpuRay skip = down_z(0.2, 0.2);
  skip.ignore = hit->scene_triangle;
  ASSERT_TRUE(intersect(cpu, skip));
  EXPECT_EQ(intersect(cpu, skip)->instance, 0u);
}

TEST(CpuTracerIntersect, BarycentricsOfAGeneralTriangle) {
  Scene s;
  s.materials.push_back({});
  scene::Primitive p;
  p.positions = {{0.3f, -1.2f, 0.7f}, {2.1f, 0.4f, -0.9f}, {-0.8f, 1.9f, 0.2f}};
  p.indices = {0, 1, 2};
  s.meshes.push_back({"general", {p}});
  s.instances.push_back({"i", {0}, glm::mat4(1.0f), 0});
  const CpuScene cpu = build_cpu_scene(s, frame_of(s));
  const glm::dvec3 p0(p.positions[0]), p1(p.positions[1]), p2(p.positions[2]);
  const double u = 0.31, v = 0.42;
  const glm::dvec3 target = (1 - u - v) * p0 + u * p1 + v * p2;
  const glm::dvec3 origin(3.0, 2.0, 5.0);
  const auto hit = intersect(cpu, CpuRay{origin, target - origin});
  ASSERT_TRUE(hit);
  EXPECT_NEAR(hit->u, u, 1e-12);
  EXPECT_NEAR(hit->v, v, 1e-12);
  EXPECT_NEAR(hit->t, 1.0, 1e-12);  // t is in units of the (unnormalised) direction
  const glm::dvec3 ng = glm::normalize(glm::cross(p1 - p0, p2 - p0));
  EXPECT_NEAR(glm::length(hit->geometric_normal - ng), 0.0, 1e-12);
}

TEST(CpuTracerIntersect, BackFaceIsHitWithTheFrontNormal) {
  const Scene s = triangle_scene({glm::mat4(1.0f)});
  const CpuScene cpu = build_cpu_scene(s, frame_of(s));
  const auto hit = intersect(cpu, CpuRay{{0.2, 0.2, -1.0}, {0.0, 0.0, 1.0}});
  ASSERT_TRUE(hit);
  EXPECT_DOUBLE_EQ(hit->t, 1.0);
  EXPECT_EQ(hit->geometric_normal, glm::dvec3(0, 0, 1));  // dot(dir, ng) > 0: a back-face hit
}

TEST(CpuTracerIntersect, TransformsMoveTrianglesAndNormals) {
  // Rotate +z to +x, scale unevenly and translate: the normal follows the inverse transpose.
  glm::mat4 m = translate(5, 0, 0) * glm::rotate(glm::mat4(1.0f), glm::half_pi<float>(),
                                                  glm::vec3(0, 1, 0));
  m = m * glm::scale(glm::mat4(1.0f), {2.0f, 3.0f, 4.0f});
  const Scene s = triangle_scene({m});
  const CpuScene cpu = build_cpu_scene(s, frame_of(s));
  ASSERT_EQ(cpu.triangles.size(), 1u);
  EXPECT_NEAR(glm::length(cpu.triangles[0].ng - glm::dvec3(1, 0, 0)), 0.0, 1e-6);
  EXPECT_NEAR(glm::length(cpu.triangles[0].n0 - glm::dvec3(1, 0, 0)), 0.0, 1e-6);
  const auto hit = intersect(cpu, CpuRay{{9.0, 0.5, -0.5}, {-1.0, 0.0, 0.0}});
  ASSERT_TRUE(hit);
  EXPECT_NEAR(hit->t, 4.0, 1e-6);
}

TEST(CpuTracerIntersect, MirroringKeepsTheObjectFrontFace) {
  // Mirrored in x, the world winding turns clockwise, yet the front face is still the object's +z.
  const Scene s = triangle_scene({glm::scale(glm::mat4(1.0f), {-1.0f, 1.0f, 1.0f})});
  const CpuScene cpu = build_cpu_scene(s, frame_of(s));
  const auto hit = intersect(cpu, down_z(-0.2, 0.2));
  ASSERT_TRUE(hit);
  EXPECT_EQ(hit->geometric_normal, glm::dvec3(0, 0, 1));
  EXPECT_NEAR(glm::length(cpu.triangles[0].n0 - glm::dvec3(0, 0, 1)), 0.0, 1e-12);
}

TEST(CpuTracerIntersect, ReportsPrimitiveTriangleAndLod) {
  Scene s;
  s.materials.push_back({});
  scene::Primitive two = unit_triangle(10.0f);
  const scene::Primitive second = unit_triangle(20.0f);
  two.positions.insert(two.positions.end(), second.positions.begin(), second.positions.end());
  two.normals.insert(two.normals.end(), second.normals.begin(), second.normals.end());
  two.uvs.insert(two.uvs.end(), second.uvs.begin(), second.uvs.end());
  two.indices = {0, 1, 2, 3, 4, 5};
  s.meshes.push_back({"lod0", {unit_triangle(100.0f)}});
  s.meshes.push_back({"lod1", {unit_triangle(), two}});
  s.instances.push_back({"i", {0, 1}, glm::mat4(1.0f), 0});
  FrameState f = frame_of(s);
  f.lods[0] = 1;
  const CpuScene cpu = build_cpu_scene(s, f);
  const auto hit = intersect(cpu, down_z(20.2, 0.2));
  ASSERT_TRUE(hit);
  EXPECT_EQ(hit->primitive, 1u);
  EXPECT_EQ(hit->triangle, 1u);
  EXPECT_FALSE(intersect(cpu, down_z(100.2, 0.2)));  // LoD 0 is not in use
}

TEST(CpuTracerIntersect, RejectsFrameStatesThatDoNotFit) {
  const Scene s = triangle_scene({glm::mat4(1.0f)});
  FrameState f = frame_of(s);
  f.lods[0] = 1;
  EXPECT_THROW(build_cpu_scene(s, f), std::invalid_argument);
  f = frame_of(s);
  f.transforms.push_back(glm::mat4(1.0f));
  EXPECT_THROW(build_cpu_scene(s, f), std::invalid_argument);
  Scene bad = s;
  bad.meshes[0].primitives[0].indices = {0, 1, 7};
  EXPECT_THROW(build_cpu_scene(bad, frame_of(bad)), std::invalid_argument);
}

TEST(CpuTracerIntersect, CameraRaysFollowTheGpuConvention) {
  scene::Camera cam;
  cam.position = {1.0f, 2.0f, 3.0f};
  cam.yfov = 0.9f;
  // Pixel centre of a 3x3 image looks straight down -Z.
  const CpuRay centre = camera_ray(cam, 3, 3, 1, 1, 0.5, 0.5);
  EXPECT_EQ(centre.origin, glm::dvec3(1, 2, 3));
  EXPECT_NEAR(glm::length(centre.direction - glm::dvec3(0, 0, -1)), 0.0, 1e-12);
  // Top-left corner of a 4x2 image: ndc (-1, 1), x widened by the aspect ratio.
  const double t = std::tan(0.45);
  const glm::dvec3 corner = glm::normalize(glm::dvec3(-t * 2.0, t, -1.0));
  EXPECT_NEAR(glm::length(camera_ray(cam, 4, 2, 0, 0, 0.0, 0.0).direction - corner), 0.0, 1e-7);
  // Turned 90 degrees about +Y, the camera looks down -X.
  cam.orientation = glm::angleAxis(glm::half_pi<float>(), glm::vec3(0, 1, 0));
  const CpuRay turned = camera_ray(cam, 3, 3, 1, 1, 0.5, 0.5);
  EXPECT_NEAR(glm::length(turned.direction - glm::dvec3(-1, 0, 0)), 0.0, 1e-6);
}

}  // namespace
}  // namespace strata::test
