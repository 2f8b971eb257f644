#include "render/restir/layer_count.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <vector>

#include "render/ray_probe.h"
#include "restir/layer_data.h"

namespace strata::render {
namespace {

// Whether the hit's triangle faces the ray (glTF: counter-clockwise seen from the front face).
bool front_facing(const scene::Scene& scene, const scene::FrameState& frame, const gpu::GpuProbeHit& h, const glm::vec3& dir) {
  if (h.instance >= scene.instances.size()) return false;
  const auto& inst = scene.instances[h.instance];
  const auto& mesh = scene.meshes[inst.lod_meshes[frame.lods[h.instance]]];
  if (h.geometry >= mesh.primitives.size()) return false;
  const auto& prim = mesh.primitives[h.geometry];
  if (3 * size_t(h.triangle) + 2 >= prim.indices.size()) return false;
  const glm::mat4& m = frame.transforms[h.instance];
  glm::vec3 p[3];
  for (int v = 0; v < 3; ++v) p[v] = glm::vec3(m * glm::vec4(prim.positions[prim.indices[3 * h.triangle + v]], 1.0f));
  return glm::dot(glm::cross(p[1] - p[0], p[2] - p[0]), dir) < 0.0f;
}

}  // namespace

LayerCount measure_layers(const gpu::Context& ctx, const scene::Scene& scene, const scene::FrameState& frame, uint32_t width,
                          uint32_t height) {
  // The grid: at most 64 x 64 pixel-centre rays spread over the image, in its aspect.
  const uint32_t gx = std::min<uint32_t>(64, width), gy = std::min<uint32_t>(64, height);
  const auto& cam = frame.camera;
  const float tan_half = std::tan(0.5f * cam.yfov), aspect = float(width) / float(height);
  const glm::vec3 forward = cam.orientation * glm::vec3(0, 0, -1), right = cam.orientation * glm::vec3(1, 0, 0) * (tan_half * aspect),
                  up = cam.orientation * glm::vec3(0, 1, 0) * tan_half;
  std::vector<ProbeRay> rays;
  for (uint32_t y = 0; y < gy; ++y)
    for (uint32_t x = 0; x < gx; ++x) {
      const float u = (float(x) + 0.5f) / float(gx) * 2.0f - 1.0f, v = 1.0f - (float(y) + 0.5f) / float(gy) * 2.0f;
      rays.push_back({cam.position, glm::normalize(forward + u * right + v * up), 0.0f, 1e30f});
    }
  // Walk every ray on through its surfaces, one probe per step: the first surface is layer 0, each
  // front face behind it one deeper (restir/layer_data.h).
  RayProbe probe(ctx, scene);
  std::vector<uint32_t> deep(rays.size(), 0);
  std::vector<bool> hit_any(rays.size(), false), walking(rays.size(), true);
  for (uint32_t step = 0; step < 2 * gpu::LAYERS_MAX; ++step) {
    std::vector<size_t> index;
    std::vector<ProbeRay> batch;
    for (size_t i = 0; i < rays.size(); ++i)
      if (walking[i]) {
        index.push_back(i);
        batch.push_back(rays[i]);
      }
    if (batch.empty()) break;
    const auto hits = probe.trace(frame, batch);
    for (size_t j = 0; j < hits.size(); ++j) {
      const size_t i = index[j];
      const auto& h = hits[j];
      if (h.t < 0.0f) {
        walking[i] = false;
        continue;
      }
      if (!hit_any[i]) hit_any[i] = true;
      else if (front_facing(scene, frame, h, rays[i].direction)) deep[i]++;
      if (deep[i] + 1 >= gpu::LAYERS_MAX) walking[i] = false;
      rays[i].t_min = h.t + std::max(h.t * 1e-4f, 1e-5f);  // just beyond it (restir/layers.glsl step_beyond)
    }
  }
  const auto surfaces = double(std::count(hit_any.begin(), hit_any.end(), true));
  LayerCount r;
  std::string shares;
  for (uint32_t j = 1; j < gpu::LAYERS_MAX; ++j) {
    const auto reach = double(std::count_if(deep.begin(), deep.end(), [&](uint32_t d) { return d >= j; }));
    const double share = surfaces > 0 ? reach / surfaces : 0.0;
    if (share <= 0.0) break;
    char part[64];
    std::snprintf(part, sizeof part, "%s%.1f%% reach layer %u", shares.empty() ? "" : ", ", 100.0 * share, j);
    shares += part;
    if (share >= k_layer_share) r.layers = j + 1;
  }
  char head[160];
  std::snprintf(head, sizeof head, "auto: of %u x %u pixel-centre rays on the scene's first frame, %.0f hit a surface", gx, gy, surfaces);
  char tail[96];
  std::snprintf(tail, sizeof tail, "; a deep layer is kept while at least %.0f%% of them reach it", 100.0 * k_layer_share);
  r.reason = std::string(head) + (shares.empty() ? "; none reaches a surface behind its first" : "; " + shares) + tail;
  return r;
}

}  // namespace strata::render
