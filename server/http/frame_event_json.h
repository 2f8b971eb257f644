#pragma once
// One rendered frame as the dashboard's event (a JSON object): the session, scene and method, the
// resolution, per-pass GPU ms, server latency (queued + render), history reset, shift failures by
// pass and reason, reuse counters, domain statistics (active domains by layer, disoccluded pixels
// and how many were covered), and optionally a small PNG thumbnail as a data URL. The frame path
// only copies the numbers and box-filters the thumbnail; the PNG and the text are made once, by the
// first viewer thread that sends the event.
#include <memory>
#include <mutex>
#include <optional>
#include <string>

#include <nlohmann/json.hpp>

#include "image/image.h"
#include "service/frame_observer.h"

namespace strata::http {

constexpr unsigned k_thumbnail_width = 96;  // pixels; the height keeps the aspect ratio

class DashboardEvent {
 public:
  DashboardEvent(nlohmann::json fields, std::optional<image::Image> thumbnail, float exposure);
  explicit DashboardEvent(std::string text);  // ready-made text
  // The whole JSON object as text; thread-safe, made on the first call.
  const std::string& text() const;

 private:
  mutable nlohmann::json fields_;
  std::optional<image::Image> thumbnail_;
  float exposure_ = 0.0f;
  mutable std::once_flag once_;
  mutable std::string text_;
};

std::shared_ptr<const DashboardEvent> make_frame_event(const service::FrameEvent& event, bool with_thumbnail);

// A box-filtered copy of `img` at most `width` pixels wide.
image::Image downscale(const image::Image& img, unsigned width);
// A tonemapped PNG of `img`, base64, in a data URL.
std::string png_data_url(const image::Image& img, float exposure);

}  // namespace strata::http
