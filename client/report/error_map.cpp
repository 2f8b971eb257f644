// Error maps as 8-bit PNGs with the magma colour map (see report.h), written by image::encode_png_rgb8.
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <string>

#include "image/image.h"
#include "report/colormap.h"
#include "report/report.h"

namespace strata::report {
namespace detail {
namespace {

// matplotlib's magma (BIDS colormaps, CC0) sampled at entries 0, 16, ..., 240 and 255 of its
// 256-entry table, placed at t = i / 16.
constexpr int kStops = 17;
constexpr float kMagma[kStops][3] = {
    {0.001462f, 0.000466f, 0.013866f}, {0.039608f, 0.031090f, 0.133515f},
    {0.113094f, 0.065492f, 0.276784f}, {0.211718f, 0.061992f, 0.418647f},
    {0.316654f, 0.071690f, 0.485380f}, {0.414709f, 0.110431f, 0.504662f},
    {0.512831f, 0.148179f, 0.507648f}, {0.613617f, 0.181811f, 0.498536f},
    {0.716387f, 0.214982f, 0.475290f}, {0.816914f, 0.255895f, 0.436461f},
    {0.904281f, 0.319610f, 0.388137f}, {0.960949f, 0.418323f, 0.359630f},
    {0.986700f, 0.535582f, 0.382210f}, {0.996096f, 0.653659f, 0.446213f},
    {0.996898f, 0.769591f, 0.534892f}, {0.992440f, 0.884330f, 0.640099f},
    {0.987053f, 0.991438f, 0.749504f},
};

}  // namespace

std::array<uint8_t, 3> magma(float t) {
  if (!(t >= 0.0f)) t = std::isnan(t) ? 1.0f : 0.0f;
  if (t > 1.0f) t = 1.0f;
  const float x = t * float(kStops - 1);
  const int i = std::min(int(x), kStops - 2);
  const float f = x - float(i);
  std::array<uint8_t, 3> rgb{};
  for (int c = 0; c < 3; ++c) {
    const float v = kMagma[i][c] + (kMagma[i + 1][c] - kMagma[i][c]) * f;
    rgb[c] = static_cast<uint8_t>(std::lround(std::clamp(v, 0.0f, 1.0f) * 255.0f));
  }
  return rgb;
}

}  // namespace detail

std::vector<uint8_t> error_map_png(const std::vector<float>& values, uint32_t width, uint32_t height,
                                   float max_value) {
  const std::string size = std::to_string(width) + "x" + std::to_string(height);
  if (width == 0 || height == 0) throw ReportError("error_map_png: zero-size map (" + size + ")");
  if (values.size() != size_t(width) * height) {
    throw ReportError("error_map_png: " + std::to_string(values.size()) + " values for a " + size + " map");
  }
  if (!(max_value > 0.0f) || !std::isfinite(max_value)) {
    throw ReportError("error_map_png: max_value " + std::to_string(max_value) + " is not a positive number");
  }
  // libpng takes the row stride as a signed 32-bit value.
  if (width > uint32_t(INT32_MAX / 3) || height > uint32_t(INT32_MAX)) {
    throw ReportError("error_map_png: " + size + " exceeds the PNG writer's limits");
  }
  std::vector<uint8_t> rgb(3 * values.size());
  for (size_t i = 0; i < values.size(); ++i) {
    const auto c = detail::magma(values[i] / max_value);
    std::memcpy(&rgb[3 * i], c.data(), 3);
  }

  try {
    return image::encode_png_rgb8(rgb, width, height);
  } catch (const image::ImageError& e) {
    throw ReportError(std::string("error_map_png: ") + e.what());
  }
}

}  // namespace strata::report
