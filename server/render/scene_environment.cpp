#include "render/scene_environment.h"

#include <vector>

#include "include/environment_data.h"

namespace strata::render {
namespace {

constexpr double kPi = 3.14159265358979323846;

}  // namespace

SceneEnvironment::SceneEnvironment(const gpu::Context& ctx, const scene::EnvironmentMap& map) {
  std::vector<glm::vec4> texels(map.radiance.size());
  for (size_t i = 0; i < texels.size(); ++i) texels[i] = glm::vec4(map.radiance[i] * map.intensity, 0.0f);
  radiance_ = gpu::make_buffer<glm::vec4>(ctx, texels, gpu::k_storage_usage, gpu::Memory::Device, "environment radiance");
  conditional_ = gpu::make_buffer<float>(ctx, map.conditional_cdf, gpu::k_storage_usage, gpu::Memory::Device, "environment cdf");
  marginal_ = gpu::make_buffer<float>(ctx, map.marginal_cdf, gpu::k_storage_usage, gpu::Memory::Device, "environment cdf");
  gpu::GpuEnvironmentMap r{};
  r.radiance = gpu::address_words(radiance_.address());
  r.conditional = gpu::address_words(conditional_.address());
  r.marginal = gpu::address_words(marginal_.address());
  r.width = map.width;
  r.height = map.height;
  r.rotation_cos = std::cos(map.rotation);
  r.rotation_sin = std::sin(map.rotation);
  record_ = gpu::Buffer(ctx, sizeof r, gpu::k_storage_usage, gpu::Memory::Device, "environment map");
  record_.upload(&r, sizeof r);
}

double SceneEnvironment::power(const scene::EnvironmentMap& map, double scene_radius) {
  // Mean luminance over solid angle: texel (i, j) spans 2 pi^2 sin(theta_j) / (w h) steradians, and
  // weight_sum is the sum of Y sin(theta_j) (scene/environment_map.h), so the mean over the
  // sphere's 4 pi is weight_sum pi / (2 w h).
  const double mean = double(map.intensity) * map.weight_sum * kPi / (2.0 * double(map.width) * double(map.height));
  return kPi * mean * kPi * scene_radius * scene_radius;
}

}  // namespace strata::render
