#pragma once
// One rendered frame as the dashboard's event (a JSON object): the session, scene and method, the
// resolution, per-pass GPU ms, server latency (queued + render), history reset, shift failures by
// pass and reason, reuse counters, domain statistics (active domains by layer, disoccluded pixels
// and how many were covered), and optionally a small PNG thumbnail as a data URL.
#include <string>

#include "service/frame_observer.h"

namespace strata::http {

constexpr unsigned k_thumbnail_width = 96;  // pixels; the height keeps the aspect ratio

std::string frame_event_json(const service::FrameEvent& event, bool with_thumbnail);

// A box-filtered copy at most `width` pixels wide, tonemapped PNG, base64 in a data URL.
std::string thumbnail_data_url(const service::FrameEvent& event, unsigned width);

}  // namespace strata::http
