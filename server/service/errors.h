#pragma once
// Errors that leave the service as gRPC statuses. Every message names the field and the limit.
#include <stdexcept>
#include <string>

#include <grpcpp/support/status.h>

namespace strata::service {

struct ServiceError : std::runtime_error {
  ServiceError(grpc::StatusCode status_code, const std::string& message)
      : std::runtime_error(message), code(status_code) {}
  grpc::StatusCode code;
};

[[noreturn]] inline void fail(grpc::StatusCode code, const std::string& message) { throw ServiceError(code, message); }
[[noreturn]] inline void fail_invalid(const std::string& message) { fail(grpc::StatusCode::INVALID_ARGUMENT, message); }

// ServiceError keeps its code; scene and image input errors and std::invalid_argument are
// INVALID_ARGUMENT; GPU errors and anything else are INTERNAL (with the message).
grpc::Status status_from_exception(const std::exception& e);

// Runs `f`, turning any exception into a status.
template <class F>
grpc::Status guarded(F&& f) {
  try {
    f();
    return grpc::Status::OK;
  } catch (const std::exception& e) {
    return status_from_exception(e);
  }
}

}  // namespace strata::service
