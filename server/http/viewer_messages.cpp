#include "http/viewer_messages.h"

#include <google/protobuf/util/json_util.h>

#include "scene/transform.h"
#include "service/errors.h"

namespace strata::http {

using service::fail_invalid;


nlohmann::json proto_json(const google::protobuf::Message& m) {
  std::string out;
  google::protobuf::util::JsonPrintOptions o;
  o.preserve_proto_field_names = true;
  o.always_print_primitive_fields = true;
  if (!google::protobuf::util::MessageToJsonString(m, &out, o).ok()) return nullptr;
  return nlohmann::json::parse(out, nullptr, false);
}

// A message field as a proto (proto3 JSON: proto or lowerCamelCase names, "NaN"/"Infinity" for
// floats); INVALID_ARGUMENT naming `field` when it does not parse (unknown fields included).
void proto_from_json(const nlohmann::json& j, google::protobuf::Message* m, const std::string& field) {
  if (!j.is_object()) fail_invalid(field + " must be a JSON object (strata.v1." + m->GetDescriptor()->name() + ")");
  google::protobuf::util::JsonParseOptions o;
  o.ignore_unknown_fields = false;
  const auto st = google::protobuf::util::JsonStringToMessage(j.dump(), m, o);
  if (!st.ok()) fail_invalid(field + " is not a strata.v1." + m->GetDescriptor()->name() + ": " + std::string(st.message()));
}

nlohmann::json vec3_json(const glm::vec3& v) { return {{"x", v.x}, {"y", v.y}, {"z", v.z}}; }
nlohmann::json quat_json(const glm::quat& q) { return {{"w", q.w}, {"x", q.x}, {"y", q.y}, {"z", q.z}}; }

// As strata.v1.Camera in proto JSON, so that the page can send it back as it is.
nlohmann::json camera_json(const scene::Camera& c) {
  return {{"position", vec3_json(c.position)}, {"orientation", quat_json(c.orientation)}, {"vertical_fov", c.yfov},
          {"aperture", c.aperture}, {"focus_distance", c.focus_distance}, {"shutter", c.shutter}};
}

nlohmann::json transform_json(const glm::mat4& m) {
  const auto k = scene::decompose_trs(m);
  return {{"translation", vec3_json(k.translation)}, {"rotation", quat_json(k.rotation)}, {"scale", vec3_json(k.scale)}};
}

std::string type_of(const nlohmann::json& msg) {
  if (!msg.contains("type") || !msg["type"].is_string())
    fail_invalid("a message needs \"type\": one of hello, create, attach, input, pick, ack, ping");
  return msg["type"].get<std::string>();
}

double number(const nlohmann::json& msg, const char* key, const std::string& type) {
  if (!msg.contains(key) || !msg[key].is_number())
    fail_invalid(type + "." + key + " is required and must be a number");
  return msg[key].get<double>();
}

int close_code(grpc::StatusCode code) {
  switch (code) {
    case grpc::StatusCode::OK: return 1000;
    case grpc::StatusCode::INVALID_ARGUMENT:
    case grpc::StatusCode::FAILED_PRECONDITION:
    case grpc::StatusCode::OUT_OF_RANGE: return 4400;
    case grpc::StatusCode::UNAUTHENTICATED: return 4401;
    case grpc::StatusCode::PERMISSION_DENIED: return 4403;
    case grpc::StatusCode::NOT_FOUND: return 4404;
    case grpc::StatusCode::ALREADY_EXISTS:
    case grpc::StatusCode::ABORTED: return 4409;
    case grpc::StatusCode::RESOURCE_EXHAUSTED: return 4429;
    case grpc::StatusCode::UNAVAILABLE: return 4503;
    case grpc::StatusCode::CANCELLED: return 1001;
    default: return 4500;
  }
}

}  // namespace strata::http
