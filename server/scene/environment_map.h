#pragma once
// Environment maps: an equirectangular HDR image (Radiance .hdr or OpenEXR) loaded into
// EnvironmentMap, its direction <-> UV mapping, and importance sampling by luminance x solid angle
// (piecewise constant in UV: a row by the marginal CDF, a column by the row's conditional CDF,
// uniform within the texel). The solid angle of UV cell du dv is 2 pi^2 sin(theta) du dv, so the
// density over directions is p(u, v) / (2 pi^2 sin(theta)) with theta the direction's own polar
// angle: it integrates to 1 over the sphere exactly, whatever the weights.
#include <cstdint>
#include <filesystem>
#include <span>
#include <string>

#include "scene/scene.h"

namespace strata::scene {

struct EnvironmentOptions {
  float intensity = 1.0f;
  float rotation_degrees = 0.0f;
  uint64_t max_file_bytes = 1ull << 30;
  uint32_t max_dimension = 16384;  // width and height each
};

// Throws SceneError naming the file: not an HDR image, undecodable, over a limit, a texel that is
// not finite or negative, a bad intensity or rotation.
EnvironmentMap load_environment_map(const std::filesystem::path& path, const EnvironmentOptions& options = {});
EnvironmentMap decode_environment_map(std::span<const uint8_t> bytes, const std::string& label,
                                      const EnvironmentOptions& options = {});

// Fills the sampling tables of `map` from its radiance.
void build_environment_tables(EnvironmentMap& map);

// World direction of UV (u, v) in [0, 1]^2, and back (rotation applied).
glm::vec3 environment_direction(const EnvironmentMap& map, glm::vec2 uv);
glm::vec2 environment_uv(const EnvironmentMap& map, glm::vec3 direction);

struct EnvironmentSample {
  glm::vec3 direction{0.0f};
  float pdf = 0.0f;  // per unit solid angle
};
// `u` uniform in [0, 1)^2. A black map has no sample (pdf 0).
EnvironmentSample sample_environment(const EnvironmentMap& map, glm::vec2 u);
float environment_pdf(const EnvironmentMap& map, glm::vec3 direction);
// Radiance of the texel `direction` falls in, times the intensity.
glm::vec3 environment_radiance(const EnvironmentMap& map, glm::vec3 direction);

}  // namespace strata::scene
