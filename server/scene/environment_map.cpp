#include "scene/environment_map.h"

#include <algorithm>
#include <cmath>
#include <fstream>

#include "image/image.h"
#include "include/environment_data.h"
#include "image/texture_decode.h"

namespace strata::scene {
namespace {

constexpr double kPi = 3.14159265358979323846;

float luminance(const glm::vec3& c) { return 0.2126f * c.r + 0.7152f * c.g + 0.0722f * c.b; }  // Rec. 709

std::string number(double v) {
  char buf[48];
  std::snprintf(buf, sizeof buf, "%g", v);
  return buf;
}

// Index k with cdf[k] <= x < cdf[k + 1] (cdf ascending from 0 to 1, n + 1 entries), skipping
// empty intervals.
size_t find_interval(const float* cdf, size_t n, float x) {
  const float* upper = std::upper_bound(cdf, cdf + n + 1, x);
  size_t k = upper == cdf ? 0 : size_t(upper - cdf) - 1;
  k = std::min(k, n - 1);
  while (k > 0 && !(cdf[k + 1] > cdf[k])) --k;  // x at the top of an empty tail
  return k;
}

// Probability of texel (i, j): that of its row times that of its column in the row (the same
// differences of the same float tables as the device takes).
double texel_probability(const EnvironmentMap& map, size_t i, size_t j) {
  const float* row = &map.conditional_cdf[j * (map.width + 1)];
  const float p_row = map.marginal_cdf[j + 1] - map.marginal_cdf[j];
  const float p_col = row[i + 1] - row[i];
  return double(p_row) * double(p_col);
}

}  // namespace

void build_environment_tables(EnvironmentMap& map) {
  const size_t w = map.width, h = map.height;
  map.conditional_cdf.assign(h * (w + 1), 0.0f);
  map.marginal_cdf.assign(h + 1, 0.0f);
  std::vector<double> row_sums(h, 0.0);
  double total = 0.0;
  for (size_t j = 0; j < h; ++j) {
    const double sin_theta = std::sin(kPi * (double(j) + 0.5) / double(h));
    float* cdf = &map.conditional_cdf[j * (w + 1)];
    double sum = 0.0;
    for (size_t i = 0; i < w; ++i) {
      sum += double(luminance(map.radiance[j * w + i])) * sin_theta;
      cdf[i + 1] = float(sum);
    }
    for (size_t i = 1; i <= w; ++i) cdf[i] = sum > 0.0 ? float(double(cdf[i]) / sum) : float(double(i) / double(w));
    cdf[w] = 1.0f;
    row_sums[j] = sum;
    total += sum;
  }
  double running = 0.0;
  for (size_t j = 0; j < h; ++j) {
    running += row_sums[j];
    map.marginal_cdf[j + 1] = total > 0.0 ? float(running / total) : float(double(j + 1) / double(h));
  }
  map.marginal_cdf[h] = 1.0f;
  map.weight_sum = total;
}

glm::vec3 environment_direction(const EnvironmentMap& map, glm::vec2 uv) {
  return gpu::environment_map_direction(uv, std::cos(map.rotation), std::sin(map.rotation));
}

glm::vec2 environment_uv(const EnvironmentMap& map, glm::vec3 direction) {
  return gpu::environment_map_uv(glm::normalize(direction), std::cos(map.rotation), std::sin(map.rotation));
}

float environment_pdf(const EnvironmentMap& map, glm::vec3 direction) {
  if (!(map.weight_sum > 0.0)) return 0.0f;
  const glm::vec2 uv = environment_uv(map, direction);
  const glm::uvec2 t = gpu::environment_map_texel(uv, map.width, map.height);
  return gpu::environment_map_solid_angle_pdf(float(texel_probability(map, t.x, t.y)), map.width, map.height, uv.y);
}

EnvironmentSample sample_environment(const EnvironmentMap& map, glm::vec2 u) {
  if (!(map.weight_sum > 0.0)) return {};
  const size_t j = find_interval(map.marginal_cdf.data(), map.height, u.y);
  const float* row = &map.conditional_cdf[j * (map.width + 1)];
  const size_t i = find_interval(row, map.width, u.x);
  const float dv = (u.y - map.marginal_cdf[j]) / (map.marginal_cdf[j + 1] - map.marginal_cdf[j]);
  const float du = (u.x - row[i]) / (row[i + 1] - row[i]);
  const glm::vec2 uv((float(i) + std::clamp(du, 0.0f, 1.0f)) / float(map.width),
                     (float(j) + std::clamp(dv, 0.0f, 1.0f)) / float(map.height));
  EnvironmentSample out;
  out.direction = environment_direction(map, uv);
  out.pdf = gpu::environment_map_solid_angle_pdf(float(texel_probability(map, i, j)), map.width, map.height, uv.y);
  return out;
}

glm::vec3 environment_radiance(const EnvironmentMap& map, glm::vec3 direction) {
  const glm::uvec2 t = gpu::environment_map_texel(environment_uv(map, direction), map.width, map.height);
  return map.radiance[size_t(t.y) * map.width + t.x] * map.intensity;
}

EnvironmentMap decode_environment_map(std::span<const uint8_t> bytes, const std::string& label,
                                      const EnvironmentOptions& options) {
  const std::string what = "environment file '" + label + "'";
  if (!std::isfinite(options.intensity) || options.intensity < 0.0f)
    throw SceneError(what + ": intensity = " + number(options.intensity) + " is not a finite number >= 0");
  if (!std::isfinite(options.rotation_degrees))
    throw SceneError(what + ": rotation = " + number(options.rotation_degrees) + " degrees is not finite");
  image::Image decoded;
  try {
    switch (image::sniff_format(bytes)) {
      case image::EncodedFormat::kRadianceHdr:
        decoded = image::decode_radiance_hdr(bytes, options.max_dimension);
        break;
      case image::EncodedFormat::kOpenExr:
        decoded = image::decode_exr(bytes);
        break;
      default:
        throw SceneError(what + " is not an HDR image (Radiance .hdr or OpenEXR): it is " +
                         image::describe_encoded(bytes));
    }
  } catch (const image::ImageError& e) {
    throw SceneError(what + ": " + e.what());
  }
  if (decoded.width > options.max_dimension || decoded.height > options.max_dimension) {
    throw SceneLimitError(what + " is " + std::to_string(decoded.width) + " x " + std::to_string(decoded.height) +
                          " texels, over the largest environment dimension (" + std::to_string(options.max_dimension) + ")");
  }
  EnvironmentMap map;
  map.name = label;
  map.width = decoded.width;
  map.height = decoded.height;
  map.intensity = options.intensity;
  map.rotation = float(double(options.rotation_degrees) * kPi / 180.0);
  map.radiance.resize(size_t(map.width) * map.height);
  for (uint32_t y = 0; y < map.height; ++y) {
    for (uint32_t x = 0; x < map.width; ++x) {
      const float* p = decoded.pixel(x, y);
      for (int c = 0; c < 3; ++c) {
        if (!std::isfinite(p[c]) || p[c] < 0.0f) {
          throw SceneError(what + ": texel (" + std::to_string(x) + ", " + std::to_string(y) + ") channel " +
                           "RGB"[c] + " = " + number(p[c]) + " is not a finite non-negative radiance");
        }
      }
      map.radiance[size_t(y) * map.width + x] = glm::vec3(p[0], p[1], p[2]);
    }
  }
  build_environment_tables(map);
  return map;
}

EnvironmentMap load_environment_map(const std::filesystem::path& path, const EnvironmentOptions& options) {
  const std::string label = path.string();
  std::error_code ec;
  if (!std::filesystem::is_regular_file(path, ec))
    throw SceneError("environment file '" + label + "' does not exist or is not a regular file");
  const uint64_t size = std::filesystem::file_size(path, ec);
  if (ec) throw SceneError("environment file '" + label + "' cannot be read: " + ec.message());
  if (size > options.max_file_bytes) {
    throw SceneLimitError("environment file '" + label + "' is " + std::to_string(size) +
                          " bytes, over the environment file limit (" + std::to_string(options.max_file_bytes) + ")");
  }
  std::ifstream in(path, std::ios::binary);
  std::vector<uint8_t> bytes(size);
  if (!in.read(reinterpret_cast<char*>(bytes.data()), std::streamsize(size)))
    throw SceneError("environment file '" + label + "' cannot be read");
  return decode_environment_map(bytes, label, options);
}

}  // namespace strata::scene
