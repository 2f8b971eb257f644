#include "http/instance_pick.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include <glm/gtc/quaternion.hpp>

namespace strata::http {
namespace {

// Moller-Trumbore; the distance along `dir`, or nullopt.
std::optional<float> hit_triangle(const glm::vec3& o, const glm::vec3& dir, const glm::vec3& a, const glm::vec3& b,
                                  const glm::vec3& c) {
  const glm::vec3 e1 = b - a, e2 = c - a, p = glm::cross(dir, e2);
  const float det = glm::dot(e1, p);
  if (std::abs(det) < 1e-12f) return std::nullopt;
  const float inv = 1.0f / det;
  const glm::vec3 s = o - a;
  const float u = glm::dot(s, p) * inv;
  if (u < 0.0f || u > 1.0f) return std::nullopt;
  const glm::vec3 q = glm::cross(s, e1);
  const float v = glm::dot(dir, q) * inv;
  if (v < 0.0f || u + v > 1.0f) return std::nullopt;
  const float t = glm::dot(e2, q) * inv;
  if (!(t > 1e-6f)) return std::nullopt;
  return t;
}

// Slab test of the ray against a box; false when it misses or the box lies beyond `max_t`.
bool hits_box(const glm::vec3& o, const glm::vec3& dir, const glm::vec3& lo, const glm::vec3& hi, float max_t) {
  float t0 = 0.0f, t1 = max_t;
  for (int k = 0; k < 3; ++k) {
    const float inv = 1.0f / dir[k];
    float a = (lo[k] - o[k]) * inv, b = (hi[k] - o[k]) * inv;
    if (a > b) std::swap(a, b);
    t0 = std::max(t0, std::isnan(a) ? t0 : a);
    t1 = std::min(t1, std::isnan(b) ? t1 : b);
    if (t0 > t1) return false;
  }
  return true;
}

}  // namespace

glm::vec3 camera_ray(const scene::Camera& camera, float u, float v, float aspect) {
  const float h = std::tan(camera.yfov * 0.5f);
  const glm::vec3 local = glm::normalize(glm::vec3((2.0f * u - 1.0f) * h * aspect, (1.0f - 2.0f * v) * h, -1.0f));
  return glm::normalize(camera.orientation * local);
}

std::optional<PickHit> pick_instance(const scene::Scene& scene, const scene::FrameState& state, float u, float v, float aspect) {
  const glm::vec3 o = state.camera.position, dir = camera_ray(state.camera, u, v, aspect);
  std::optional<PickHit> best;
  float best_t = std::numeric_limits<float>::infinity();
  for (uint32_t i = 0; i < scene.instances.size(); ++i) {
    const auto& inst = scene.instances[i];
    const uint32_t level = i < state.lods.size() ? std::min<uint32_t>(state.lods[i], uint32_t(inst.lod_meshes.size() - 1)) : inst.lod;
    const glm::mat4 m = i < state.transforms.size() ? state.transforms[i] : inst.transform;
    const auto& mesh = scene.meshes[inst.lod_meshes[level]];
    // World bounding box of the instance's vertices first: most instances are not under the cursor.
    glm::vec3 lo(std::numeric_limits<float>::infinity()), hi(-std::numeric_limits<float>::infinity());
    std::vector<glm::vec3> world;
    for (const auto& prim : mesh.primitives)
      for (const auto& p : prim.positions) {
        const glm::vec3 w = glm::vec3(m * glm::vec4(p, 1.0f));
        lo = glm::min(lo, w);
        hi = glm::max(hi, w);
        world.push_back(w);
      }
    if (world.empty() || !hits_box(o, dir, lo - 1e-4f, hi + 1e-4f, best_t)) continue;
    size_t base = 0;
    for (const auto& prim : mesh.primitives) {
      for (size_t t = 0; t + 2 < prim.indices.size(); t += 3) {
        const auto hit = hit_triangle(o, dir, world[base + prim.indices[t]], world[base + prim.indices[t + 1]],
                                      world[base + prim.indices[t + 2]]);
        if (hit && *hit < best_t) {
          best_t = *hit;
          best = PickHit{i, *hit, o + dir * *hit};
        }
      }
      base += prim.positions.size();
    }
  }
  return best;
}

}  // namespace strata::http
