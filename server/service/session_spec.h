#pragma once
// What CreateSession asked for, checked: the one place its request is validated before it touches
// the device (CreateSession and the create_session fuzz target both call check_create_session).
#include <cstdint>
#include <string>
#include <vector>

#include "render/method_table.h"
#include "render/renderer.h"
#include "service/config.h"
#include "strata/v1/render.pb.h"

namespace strata::service {

namespace v1 = ::strata::v1;

struct SessionSpec {
  // The method in use; for `method auto` restir-gather while it calibrates, then its choice.
  const render::MethodSpec* method = nullptr;
  std::string requested_method;  // as the client sent it: empty takes the default, auto
  bool auto_method = false;      // empty or "auto" (service/method_auto.h)
  v1::RenderOptions requested;  // as the client sent them
  v1::RenderOptions options;    // effective: every field set
  uint32_t width = 0, height = 0, seed = 0;
  std::vector<v1::ImageEncoding> encodings;
};

// Method, resolution, options (ranges, what the method requires, the defaults) and encodings, and
// that a scene is named; each failure is INVALID_ARGUMENT naming the field. The session id and the
// scene itself are checked where they are used (the registry, load_scene_source).
SessionSpec check_create_session(const v1::CreateSessionRequest& req, const ServiceLimits& limits);

// The renderer's settings of a checked session: its resolution, method, effective options and seed.
render::RenderSettings render_settings(const SessionSpec& spec);

}  // namespace strata::service
