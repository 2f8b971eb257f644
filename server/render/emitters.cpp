#include "render/emitters.h"

#include <cmath>
#include <cstring>
#include <numbers>
#include <numeric>

#include "render/scene_textures.h"
#include "scene/deform.h"
#include "render/punctual_lights.h"

namespace strata::render {

std::vector<gpu::GpuAliasEntry> build_alias_table(std::span<const double> weights) {
  size_t n = weights.size();
  std::vector<gpu::GpuAliasEntry> table(n, gpu::GpuAliasEntry{1.0f, 0, 0, 0});
  if (n == 0) return table;
  double sum = std::accumulate(weights.begin(), weights.end(), 0.0);
  std::vector<double> scaled(n);
  for (size_t i = 0; i < n; ++i) scaled[i] = sum > 0.0 ? weights[i] * double(n) / sum : 1.0;
  // Vose's method: pair each under-full column with an over-full one.
  std::vector<uint32_t> small, large;
  for (size_t i = 0; i < n; ++i) (scaled[i] < 1.0 ? small : large).push_back(uint32_t(i));
  while (!small.empty() && !large.empty()) {
    uint32_t s = small.back();
    small.pop_back();
    uint32_t l = large.back();
    table[s].threshold = float(scaled[s]);
    table[s].alias = l;
    scaled[l] -= 1.0 - scaled[s];
    if (scaled[l] < 1.0) {
      large.pop_back();
      small.push_back(l);
    }
  }
  // Leftovers are 1 up to rounding.
  for (uint32_t i : small) table[i] = {1.0f, i, 0, 0};
  for (uint32_t i : large) table[i] = {1.0f, i, 0, 0};
  return table;
}

glm::mat4 object_to_render(const glm::mat4& m, glm::dvec3 origin) {
  glm::mat4 r = m;
  for (int i = 0; i < 3; ++i) r[3][i] = float(double(m[3][i]) - origin[i]);
  return r;
}

EmitterTable build_emitter_table(const scene::Scene& scene, const scene::FrameState& frame, glm::dvec3 origin,
                                 double scene_radius) {
  EmitterTable t;
  std::vector<double> power;
  for (size_t i = 0; i < scene.instances.size(); ++i) {
    const auto& inst = scene.instances[i];
    const auto& mesh = scene.meshes[inst.lod_meshes[frame.lods[i]]];
    glm::mat4 m = object_to_render(frame.transforms[i], origin);
    bool mirrored = glm::determinant(glm::mat3(m)) < 0.0f;
    // A deforming instance's emitters are where its deformed vertices are this frame (the same
    // computation as the device's deformation pass: scene/deform.h).
    const std::vector<scene::SkinningMatrix> skinning =
        inst.deforms() ? scene::instance_skinning(scene, frame, i) : std::vector<scene::SkinningMatrix>{};
    for (size_t g = 0; g < mesh.primitives.size(); ++g) {
      const auto& prim = mesh.primitives[g];
      const auto& mat = scene.materials[prim.material];
      double material_lum = 0.2126 * mat.emission.r + 0.7152 * mat.emission.g + 0.0722 * mat.emission.b;
      if (!(material_lum > 0.0)) continue;
      std::vector<glm::vec3> deformed;
      if (inst.deforms()) deformed = scene::deform_primitive(prim, skinning, scene::morph_weights_at(scene, frame, i)).positions;
      const std::vector<glm::vec3>& positions = inst.deforms() ? deformed : prim.positions;
      uint32_t flags = mat.double_sided ? gpu::MATERIAL_DOUBLE_SIDED : 0u;
      float flag_bits;
      std::memcpy(&flag_bits, &flags, sizeof flags);
      for (size_t tri = 0; tri < prim.triangle_count(); ++tri) {
        // An emissive texture's triangles are selected by their integrated texture (render/scene_textures.h).
        const glm::vec3 emission = triangle_light_emission(scene, prim, tri);
        const double lum = 0.2126 * emission.r + 0.7152 * emission.g + 0.0722 * emission.b;
        if (!(lum > 0.0)) continue;
        glm::vec3 p[3];
        for (int k = 0; k < 3; ++k) p[k] = glm::vec3(m * glm::vec4(positions[prim.indices[3 * tri + size_t(k)]], 1.0f));
        if (mirrored) std::swap(p[1], p[2]);
        float area = 0.5f * glm::length(glm::cross(p[1] - p[0], p[2] - p[0]));
        if (!(area > 0.0f) || !std::isfinite(area)) continue;  // degenerate: cannot be sampled by area
        double w = lum * double(area) * (mat.double_sided ? 2.0 : 1.0);
        t.emitters.push_back({glm::vec4(p[0], area), glm::vec4(p[1], 0.0f), glm::vec4(p[2], flag_bits),
                              glm::vec4(emission, 0.0f),
                              glm::uvec4(uint32_t(i), uint32_t(g), uint32_t(tri), mirrored ? 1u : 0u)});
        power.push_back(w);
        t.total_power += w;
      }
    }
  }
  for (size_t l = 0; l < scene.lights.size(); ++l) {
    t.lights.push_back(punctual_record(scene.lights[l], frame.lights.at(l), origin));
    // The table's unit is power / pi: a diffuse triangle's weight above, L A sides, is its power
    // pi L A sides over pi (the unit sampling/emitter_pdf.h divides by on the device).
    const double w = punctual_power(scene.lights[l], scene_radius) / std::numbers::pi;
    power.push_back(w);
    t.total_power += w;
  }
  const double total = t.total_power > 0.0 ? t.total_power : 1.0;
  for (size_t i = 0; i < t.emitters.size(); ++i) t.emitters[i].p1_pmf.w = float(power[i] / total);
  for (size_t l = 0; l < t.lights.size(); ++l) t.lights[l].intensity_pmf.w = float(power[t.emitters.size() + l] / total);
  t.alias = build_alias_table(power);
  t.power = std::move(power);
  return t;
}

}  // namespace strata::render
