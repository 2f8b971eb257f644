// CreateSessionRequest as it arrives on the wire: parse, then every check CreateSession makes
// before it touches the device (method and options, resolution, encodings, session id, and the
// scene source: a built-in name, a path refused without --scene-dir, or inline .glb bytes loaded
// and held to the limits). Must end in success or a status naming the field.
#include "fuzz_support.h"
#include "service/session_spec.h"
#include "service/scene_source.h"
#include "service/session_id.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  strata::v1::CreateSessionRequest req;
  if (!req.ParseFromArray(data, int(size))) return 0;  // gRPC answers INTERNAL "failed to parse" itself
  strata::service::ServiceConfig config;  // the default limits; no scene directory
  config.limits.max_scene_bytes = 1 << 20;
  config.limits.max_instances = 256;
  strata::fuzz::expect_clean("create_session", [&] {
    using namespace strata::service;
    (void)check_create_session(req, config.limits);  // what CreateSession checks before the device
    if (!req.session_id().empty()) check_session_id(req.session_id(), "session_id");
    (void)load_scene_source(req.scene(), config);
  });
  return 0;
}
