#include "render/punctual_lights.h"

#include <algorithm>
#include <cmath>
#include <limits>

namespace strata::render {
namespace {

constexpr double kPi = 3.14159265358979323846;

double luminance(glm::vec3 c) { return 0.2126 * c.r + 0.7152 * c.g + 0.0722 * c.b; }

}  // namespace

double scene_bounding_radius(const scene::Scene& scene) {
  glm::dvec3 lo(std::numeric_limits<double>::max());
  glm::dvec3 hi(-std::numeric_limits<double>::max());
  for (const auto& inst : scene.instances) {
    const glm::dmat4 m(inst.transform);
    for (const auto& prim : scene.meshes[inst.lod_meshes[std::min<size_t>(inst.lod, inst.lod_meshes.size() - 1)]].primitives) {
      for (const auto& p : prim.positions) {
        const glm::dvec3 w(m * glm::dvec4(glm::dvec3(p), 1.0));
        lo = glm::min(lo, w);
        hi = glm::max(hi, w);
      }
    }
  }
  if (!(hi.x >= lo.x)) return 1.0;
  const double r = 0.5 * glm::length(hi - lo);
  return r > 0.0 ? r : 1.0;
}

glm::vec2 spot_angle_scale_offset(const scene::Light& light) {
  const float cos_outer = std::cos(light.outer_cone);
  const float cos_inner = std::cos(light.inner_cone);
  const float scale = 1.0f / std::max(0.001f, cos_inner - cos_outer);
  return {scale, -cos_outer * scale};
}

double punctual_power(const scene::Light& light, double scene_radius) {
  const double intensity = luminance(light.color) * double(light.intensity);
  if (!(intensity > 0.0)) return 0.0;
  switch (light.type) {
    case scene::LightType::kPoint:
      return 4.0 * kPi * intensity;
    case scene::LightType::kSpot: {
      const glm::vec2 so = spot_angle_scale_offset(light);
      const double cos_outer = std::cos(double(light.outer_cone));
      const double width = 1.0 / double(so.x);  // the falloff rises from 0 at c_o to 1 at c_o + width
      const double weighted = cos_outer + width <= 1.0 ? (1.0 - cos_outer - width) + width / 3.0
                                                       : std::pow(1.0 - cos_outer, 3.0) / (3.0 * width * width);
      return 2.0 * kPi * intensity * weighted;
    }
    case scene::LightType::kDirectional:
      return kPi * scene_radius * scene_radius * intensity;
  }
  return 0.0;
}

gpu::GpuPunctualLight punctual_record(const scene::Light& light, const glm::mat4& m, glm::dvec3 origin) {
  gpu::GpuPunctualLight r{};
  const glm::dvec3 position = glm::dvec3(m[3]) - origin;
  glm::vec3 dir = glm::mat3(m) * glm::vec3(0.0f, 0.0f, -1.0f);  // the light shines down its local -Z
  const float len = glm::length(dir);
  dir = len > 0.0f ? dir / len : glm::vec3(0.0f, 0.0f, -1.0f);
  uint32_t type = light.type == scene::LightType::kPoint  ? gpu::PUNCTUAL_POINT
                  : light.type == scene::LightType::kSpot ? gpu::PUNCTUAL_SPOT
                                                          : gpu::PUNCTUAL_DIRECTIONAL;
  r.position_range = glm::vec4(glm::vec3(position), light.range);
  r.direction_type = glm::vec4(dir, float(type));
  r.intensity_pmf = glm::vec4(light.color * light.intensity, 0.0f);
  if (light.type == scene::LightType::kSpot) r.cone = glm::vec4(spot_angle_scale_offset(light), 0.0f, 0.0f);
  return r;
}

}  // namespace strata::render
