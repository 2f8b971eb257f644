#include "service/session_spec.h"

#include "service/errors.h"
#include "service/input_checks.h"
#include "service/options.h"

namespace strata::service {

SessionSpec check_create_session(const v1::CreateSessionRequest& req, const ServiceLimits& limits) {
  SessionSpec spec;
  spec.method = &check_method(req.method(), "method");
  spec.requested_method = req.method();
  spec.auto_method = is_auto_method(req.method());
  if (!req.has_resolution()) fail_invalid("resolution is required (width and height in pixels)");
  check_resolution(req.resolution(), limits, "resolution");
  check_options(req.options(), limits, "options");
  check_method_options(*spec.method, req.options(), "options", spec.auto_method);
  spec.requested = req.options();
  spec.options = with_defaults(req.options(), *spec.method, limits, req.resolution().height());
  spec.width = req.resolution().width();
  spec.height = req.resolution().height();
  spec.seed = req.seed();
  spec.encodings = check_encodings(req.encodings(), "encodings");
  check_method_encodings(*spec.method, spec.encodings, "encodings");
  if (!req.has_scene()) fail_invalid("scene is required: set scene.builtin, scene.path or scene.glb");
  return spec;
}

render::RenderSettings render_settings(const SessionSpec& spec) {
  render::RenderSettings s;
  s.width = spec.width;
  s.height = spec.height;
  s.method = spec.method->name;
  s.spp = spec.options.spp();
  s.max_depth = spec.options.max_depth();
  s.seed = spec.seed;
  s.restir = restir_options(spec.options);
  return s;
}

}  // namespace strata::service
