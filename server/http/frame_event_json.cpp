#include "http/frame_event_json.h"

#include <algorithm>
#include <chrono>

#include <nlohmann/json.hpp>

#include "image/image.h"
#include "service/frame_message.h"
#include "service/session.h"

namespace strata::http {
namespace {

std::string base64(const std::vector<uint8_t>& bytes) {
  static constexpr char k_alphabet[] = "ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";
  std::string out;
  out.reserve((bytes.size() + 2) / 3 * 4);
  for (size_t i = 0; i < bytes.size(); i += 3) {
    const uint32_t b0 = bytes[i], b1 = i + 1 < bytes.size() ? bytes[i + 1] : 0u, b2 = i + 2 < bytes.size() ? bytes[i + 2] : 0u;
    const uint32_t v = (b0 << 16) | (b1 << 8) | b2;
    out += k_alphabet[(v >> 18) & 63];
    out += k_alphabet[(v >> 12) & 63];
    out += i + 1 < bytes.size() ? k_alphabet[(v >> 6) & 63] : '=';
    out += i + 2 < bytes.size() ? k_alphabet[v & 63] : '=';
  }
  return out;
}

}  // namespace

image::Image downscale(const image::Image& src, unsigned width) {
  image::Image t;
  if (src.width == 0 || src.height == 0) return t;
  t.width = std::min(width, src.width);
  t.height = std::max(1u, unsigned(uint64_t(src.height) * t.width / src.width));
  t.rgba.assign(size_t(t.width) * t.height * 4, 0.0f);
  // Box filter: each thumbnail pixel averages the source pixels it covers.
  for (uint32_t y = 0; y < t.height; ++y) {
    const uint32_t y0 = y * src.height / t.height, y1 = std::max(y0 + 1, (y + 1) * src.height / t.height);
    for (uint32_t x = 0; x < t.width; ++x) {
      const uint32_t x0 = x * src.width / t.width, x1 = std::max(x0 + 1, (x + 1) * src.width / t.width);
      float* out = t.pixel(x, y);
      for (uint32_t sy = y0; sy < y1; ++sy)
        for (uint32_t sx = x0; sx < x1; ++sx)
          for (int c = 0; c < 4; ++c) out[c] += src.pixel(sx, sy)[c];
      const float n = float((y1 - y0) * (x1 - x0));
      for (int c = 0; c < 4; ++c) out[c] /= n;
    }
  }
  return t;
}

std::string png_data_url(const image::Image& img, float exposure) {
  return "data:image/png;base64," + base64(image::encode_png_preview(img, exposure));
}

DashboardEvent::DashboardEvent(nlohmann::json fields, std::optional<image::Image> thumbnail, float exposure)
    : fields_(std::move(fields)), thumbnail_(std::move(thumbnail)), exposure_(exposure) {}

DashboardEvent::DashboardEvent(std::string text) : text_(std::move(text)) { std::call_once(once_, [] {}); }

const std::string& DashboardEvent::text() const {
  std::call_once(once_, [&] {
    if (thumbnail_) fields_["thumbnail"] = png_data_url(*thumbnail_, exposure_);
    text_ = fields_.dump(-1, ' ', false, nlohmann::json::error_handler_t::replace);
  });
  return text_;
}

std::shared_ptr<const DashboardEvent> make_frame_event(const service::FrameEvent& e, bool with_thumbnail) {
  const auto& f = e.frame;
  const auto& stats = f.result.stats;
  nlohmann::json j;
  j["session"] = e.session;
  j["scene"] = e.scene;
  j["method"] = e.method;
  j["frame"] = f.frame_index;
  j["t_ms"] = std::chrono::duration<double, std::milli>(std::chrono::system_clock::now().time_since_epoch()).count();
  j["width"] = f.result.image.width;
  j["height"] = f.result.image.height;
  j["gpu_ms"] = stats.gpu_ms_total;
  j["latency_ms"] = f.queued_ms + f.render_ms;
  j["queued_ms"] = f.queued_ms;
  j["render_ms"] = f.render_ms;
  nlohmann::json passes = nlohmann::json::object();
  for (const auto& p : stats.pass_ms) passes[p.pass] = passes.value(p.pass, 0.0) + p.ms;
  j["pass_ms"] = passes;
  j["history_reset"] = f.history_reset;
  if (f.history_reset) j["history_reset_reason"] = f.history_reset_reason;
  j["rays"] = stats.rays_total();

  // As the metrics do: the wire statistics name every method's counters, new ones included.
  v1::FrameStatistics wire;
  // Only methods with reuse fill the reuse statistics; the copy costs nothing for the others.
  if (!stats.reuse.empty() || !stats.shift_failures.empty()) service::fill_statistics(stats, &wire);
  const auto& reuse = wire.reuse();
  nlohmann::json failures = nlohmann::json::object(), counters = nlohmann::json::object();
  for (const auto& [k, n] : reuse.shift_failures()) failures[k] = n;
  for (const auto& [k, n] : reuse.counters()) counters[k] = n;
  j["shift_failures"] = failures;
  j["reuse"] = counters;
  nlohmann::json layers = nlohmann::json::array();
  for (auto n : reuse.active_domains_by_layer()) layers.push_back(n);
  j["domains"] = {{"active_by_layer", layers},
                  {"disoccluded", reuse.disoccluded_pixels()},
                  {"covered", reuse.disoccluded_covered()},
                  {"coverage_rate", reuse.coverage_rate()}};
  std::optional<image::Image> thumbnail;
  if (with_thumbnail && f.result.image.width > 0) thumbnail = downscale(f.result.image, k_thumbnail_width);
  return std::make_shared<const DashboardEvent>(std::move(j), std::move(thumbnail), f.exposure);
}

}  // namespace strata::http
