#pragma once
// Stamps `x-strata-instance: <instance id>` on the initial metadata of every response (every
// service, errors included), so that a client behind a proxy can tell which daemon answered it
// and a test can check that all calls of one session reached one daemon.
#include <memory>
#include <string>
#include <vector>

#include <grpcpp/support/server_interceptor.h>

namespace strata::service {

inline constexpr const char* k_instance_metadata = "x-strata-instance";
inline constexpr const char* k_session_metadata = "x-strata-session";

// The interceptor factories to give ServerBuilder::experimental().SetInterceptorCreators().
std::vector<std::unique_ptr<grpc::experimental::ServerInterceptorFactoryInterface>> instance_interceptors(std::string instance_id);

}  // namespace strata::service
