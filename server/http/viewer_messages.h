#pragma once
// The viewer socket's messages as JSON (server/http/viewer_stream.h speaks them): protos in proto3
// JSON both ways, cameras and transforms as the page reads them, the fields every message has, and
// the close code of a gRPC status.
#include <string>

#include <glm/glm.hpp>
#include <glm/gtc/quaternion.hpp>
#include <google/protobuf/message.h>
#include <grpcpp/grpcpp.h>
#include <nlohmann/json.hpp>

#include "scene/scene.h"

namespace strata::http {

nlohmann::json vec3_json(const glm::vec3& v);
nlohmann::json proto_json(const google::protobuf::Message& m);
// A message field as a proto (proto3 JSON: proto or lowerCamelCase names, "NaN"/"Infinity" for
// floats); INVALID_ARGUMENT naming `field` when it does not parse (unknown fields included).
void proto_from_json(const nlohmann::json& j, google::protobuf::Message* m, const std::string& field);
// As strata.v1.Camera in proto JSON, so that the page can send it back as it is.
nlohmann::json camera_json(const scene::Camera& c);
nlohmann::json transform_json(const glm::mat4& m);
// A message's "type" and a required number field; INVALID_ARGUMENT naming them otherwise.
std::string type_of(const nlohmann::json& msg);
double number(const nlohmann::json& msg, const char* key, const std::string& type);
// The WebSocket close code of a gRPC status (4000 + the HTTP status where one fits).
int close_code(grpc::StatusCode code);

}  // namespace strata::http
