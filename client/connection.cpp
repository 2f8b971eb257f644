#include "connection.h"

#include <algorithm>
#include <climits>

namespace strata::client {

std::string status_code_name(grpc::StatusCode code) {
  switch (code) {
    case grpc::StatusCode::OK: return "OK";
    case grpc::StatusCode::CANCELLED: return "CANCELLED";
    case grpc::StatusCode::UNKNOWN: return "UNKNOWN";
    case grpc::StatusCode::INVALID_ARGUMENT: return "INVALID_ARGUMENT";
    case grpc::StatusCode::DEADLINE_EXCEEDED: return "DEADLINE_EXCEEDED";
    case grpc::StatusCode::NOT_FOUND: return "NOT_FOUND";
    case grpc::StatusCode::ALREADY_EXISTS: return "ALREADY_EXISTS";
    case grpc::StatusCode::PERMISSION_DENIED: return "PERMISSION_DENIED";
    case grpc::StatusCode::RESOURCE_EXHAUSTED: return "RESOURCE_EXHAUSTED";
    case grpc::StatusCode::FAILED_PRECONDITION: return "FAILED_PRECONDITION";
    case grpc::StatusCode::ABORTED: return "ABORTED";
    case grpc::StatusCode::OUT_OF_RANGE: return "OUT_OF_RANGE";
    case grpc::StatusCode::UNIMPLEMENTED: return "UNIMPLEMENTED";
    case grpc::StatusCode::INTERNAL: return "INTERNAL";
    case grpc::StatusCode::UNAVAILABLE: return "UNAVAILABLE";
    case grpc::StatusCode::DATA_LOSS: return "DATA_LOSS";
    case grpc::StatusCode::UNAUTHENTICATED: return "UNAUTHENTICATED";
    default: return "code " + std::to_string(int(code));
  }
}

grpc::Status as_seen_through_proxies(const grpc::Status& status) {
  // A proxy (HAProxy) whose backend dies mid-call ends the client's HTTP/2 stream without gRPC
  // trailers, which gRPC reports as UNKNOWN "No status received". Connected directly the same
  // failure is UNAVAILABLE; report it so, saying what happened.
  if (status.error_code() == grpc::StatusCode::UNKNOWN && status.error_message() == "No status received")
    return {grpc::StatusCode::UNAVAILABLE, "the call ended without a status (the server, or the one behind a proxy, went away)"};
  return status;
}

RpcError::RpcError(const std::string& method, const grpc::Status& raw)
    : RpcError(method, as_seen_through_proxies(raw), 0) {}

RpcError::RpcError(const std::string& method, const grpc::Status& status, int)
    : std::runtime_error(method + ": " + status_code_name(status.error_code()) + ": " + status.error_message()),
      code(status.error_code()) {}

grpc::ChannelArguments channel_arguments(uint64_t max_receive_bytes, uint64_t max_send_bytes) {
  grpc::ChannelArguments args;
  args.SetMaxReceiveMessageSize(int(std::min<uint64_t>(max_receive_bytes, INT_MAX)));
  args.SetMaxSendMessageSize(int(std::min<uint64_t>(max_send_bytes, INT_MAX)));
  // gRPC's service config (gRFC A6 retry policy); retries are on by default in gRPC >= 1.40.
  args.SetServiceConfigJSON(R"({"methodConfig": [{
    "name": [{"service": "strata.v1.RenderService", "method": "GetServerStatus"},
             {"service": "strata.v1.RenderService", "method": "GetSession"},
             {"service": "strata.v1.RenderService", "method": "ListSessions"},
             {"service": "strata.v1.RenderService", "method": "ListScenes"}],
    "retryPolicy": {"maxAttempts": 4, "initialBackoff": "0.1s", "maxBackoff": "1s", "backoffMultiplier": 2,
                    "retryableStatusCodes": ["UNAVAILABLE"]}}]})");
  return args;
}

std::shared_ptr<grpc::Channel> connect(const std::string& address, uint64_t max_receive_bytes, uint64_t max_send_bytes) {
  auto args = channel_arguments(max_receive_bytes, max_send_bytes);
  return grpc::CreateCustomChannel(address, grpc::InsecureChannelCredentials(), args);
}

void set_deadline(grpc::ClientContext& ctx, std::chrono::milliseconds timeout) {
  ctx.set_deadline(std::chrono::system_clock::now() + timeout);
}

}  // namespace strata::client
