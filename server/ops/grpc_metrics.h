#pragma once
// gRPC server metrics by method and status code, named as go-grpc-prometheus names them
// (grpc_server_started_total, grpc_server_handled_total, grpc_server_handling_seconds, labels
// grpc_type, grpc_service, grpc_method, grpc_code), so that existing dashboards and alerts apply.
// A server interceptor sees every call (health checks and reflection too) and records it when the
// call ends: with the status it sent, or Canceled when it ended without sending one.
#include <memory>
#include <string>

#include <grpcpp/support/server_interceptor.h>
#include <prometheus/counter.h>
#include <prometheus/family.h>
#include <prometheus/histogram.h>
#include <prometheus/registry.h>

namespace strata::ops {

// The code's name as Go's codes.Code.String() spells it ("OK", "InvalidArgument", "Canceled", ...).
std::string grpc_code_name(int code);

class GrpcMetrics {
 public:
  explicit GrpcMetrics(prometheus::Registry& registry);
  // A factory for ServerBuilder::experimental().SetInterceptorCreators; it refers to this object,
  // which must outlive the server.
  std::unique_ptr<grpc::experimental::ServerInterceptorFactoryInterface> interceptor_factory();

  void started(const std::string& type, const std::string& service, const std::string& method);
  void handled(const std::string& type, const std::string& service, const std::string& method, int code, double seconds);

 private:
  prometheus::Family<prometheus::Counter>& started_;
  prometheus::Family<prometheus::Counter>& handled_;
  prometheus::Family<prometheus::Histogram>& seconds_;
};

}  // namespace strata::ops
