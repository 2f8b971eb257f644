#include <glm/gtc/matrix_transform.hpp>
#include <stdexcept>

#include "support/test_scenes.h"

namespace strata::test {
namespace {

// Quad with corners c0..c3 in counter-clockwise order seen from the side `n` points to.
scene::Primitive quad(glm::vec3 c0, glm::vec3 c1, glm::vec3 c2, glm::vec3 c3, glm::vec3 n, uint32_t material) {
  scene::Primitive p;
  p.positions = {c0, c1, c2, c3};
  p.normals = {n, n, n, n};
  p.uvs = {{0, 0}, {1, 0}, {1, 1}, {0, 1}};
  p.indices = {0, 1, 2, 0, 2, 3};
  p.material = material;
  return p;
}

}  // namespace

scene::Mesh quad_mesh(float h, float z0, uint32_t material) {
  scene::Mesh m;
  m.name = "quad";
  m.primitives.push_back(quad({-h, -h, z0}, {h, -h, z0}, {h, h, z0}, {-h, h, z0}, {0, 0, 1}, material));
  return m;
}

scene::Scene furnace_box(float albedo, float emission, float h) {
  scene::Scene s;
  s.name = "furnace";
  scene::Material m;
  m.name = "furnace wall";
  m.base_color = glm::vec3(albedo);
  m.metallic = 0.0f;
  m.roughness = 1.0f;
  m.specular = 0.0f;
  m.emission = glm::vec3(emission);
  s.materials.push_back(m);
  scene::Mesh box;
  box.name = "box";
  // Each face wound counter-clockwise as seen from inside (its inward normal).
  box.primitives.push_back(quad({-h, -h, -h}, {h, -h, -h}, {h, h, -h}, {-h, h, -h}, {0, 0, 1}, 0));   // z = -h, faces +z
  box.primitives.push_back(quad({-h, -h, h}, {-h, h, h}, {h, h, h}, {h, -h, h}, {0, 0, -1}, 0));     // z = +h, faces -z
  box.primitives.push_back(quad({-h, -h, -h}, {-h, h, -h}, {-h, h, h}, {-h, -h, h}, {1, 0, 0}, 0));   // x = -h, faces +x
  box.primitives.push_back(quad({h, -h, -h}, {h, -h, h}, {h, h, h}, {h, h, -h}, {-1, 0, 0}, 0));     // x = +h, faces -x
  box.primitives.push_back(quad({-h, -h, -h}, {-h, -h, h}, {h, -h, h}, {h, -h, -h}, {0, 1, 0}, 0));   // y = -h, faces +y
  box.primitives.push_back(quad({-h, h, -h}, {h, h, -h}, {h, h, h}, {-h, h, h}, {0, -1, 0}, 0));     // y = +h, faces -y
  s.meshes.push_back(box);
  scene::Instance inst;
  inst.name = "box";
  inst.lod_meshes = {0};
  s.instances.push_back(inst);
  s.camera.position = glm::vec3(0.0f);
  s.camera.yfov = 1.2f;
  return s;
}

scene::Scene two_planes(float front_half, float environment) {
  scene::Scene s;
  s.name = "two-planes";
  auto lambert = [&](const char* name, glm::vec3 albedo, glm::vec3 emission) {
    scene::Material m;
    m.name = name;
    m.base_color = albedo;
    m.specular = 0.0f;
    m.emission = emission;
    s.materials.push_back(m);
    return uint32_t(s.materials.size() - 1);
  };
  auto add = [&](const char* name, scene::Mesh mesh) {
    mesh.name = name;
    s.meshes.push_back(std::move(mesh));
    scene::Instance inst;
    inst.name = name;
    inst.lod_meshes = {uint32_t(s.meshes.size() - 1)};
    s.instances.push_back(inst);
  };
  add("back", quad_mesh(2.0f, 0.0f, lambert("back", glm::vec3(0.7f), glm::vec3(0.0f))));
  if (front_half > 0.0f) add("front", quad_mesh(front_half, 1.0f, lambert("front", {0.8f, 0.45f, 0.2f}, glm::vec3(0.0f))));
  scene::Mesh light;
  light.primitives.push_back(
      quad({1.4f, -4.0f, 0.5f}, {1.4f, 4.0f, 0.5f}, {6.0f, 4.0f, 0.5f}, {6.0f, -4.0f, 0.5f}, {0, 0, -1}, lambert("light", glm::vec3(0.0f), glm::vec3(4.0f))));
  add("light", light);
  s.environment.radiance = glm::vec3(environment);
  s.camera.position = {0.0f, 0.0f, 4.0f};
  s.camera.yfov = 0.6f;
  s.validate();
  return s;
}

uint32_t instance_named(const scene::Scene& s, const std::string& name) {
  for (uint32_t i = 0; i < s.instances.size(); ++i)
    if (s.instances[i].name == name) return i;
  throw std::runtime_error("no instance " + name);
}

scene::FrameState cornell_light_shaded(const scene::Scene& cornell) {
  scene::FrameState st = cornell.frame_state(0);
  st.transforms[instance_named(cornell, "short_box")] =
      glm::scale(glm::translate(glm::mat4(1.0f), {0.0f, 1.8f, 0.0f}), {2.0f, 0.1f, 2.0f});
  return st;
}

std::string method_test_name(const std::string& method) {
  std::string n = method;
  for (char& c : n)
    if (c == '-') c = '_';
  return n;
}

scene::FrameState lod_switched(const scene::Scene& s, uint32_t scene_frame, uint32_t f) {
  scene::FrameState st = s.frame_state(scene_frame);
  for (size_t i = 0; i < st.lods.size(); ++i)
    if (s.instances[i].lod_meshes.size() > 1) st.lods[i] = f % 2;
  return st;
}

scene::Scene white_plane(const std::string& name) {
  scene::Scene s;
  s.name = name;
  scene::Material white;
  white.name = "white";
  white.base_color = glm::vec3(1.0f);
  white.specular = 0.0f;
  s.materials.push_back(white);
  scene::Mesh m = quad_mesh(10.0f, 0.0f, 0);
  m.name = "plane";
  s.meshes.push_back(m);
  scene::Instance inst;
  inst.name = "plane";
  inst.lod_meshes = {0};
  s.instances.push_back(inst);
  s.camera.position = glm::vec3(0.0f, 0.0f, 3.0f);
  s.camera.yfov = 0.004f;
  return s;
}

}  // namespace strata::test
