#include "ops/grpc_metrics.h"

#include <array>
#include <chrono>

namespace strata::ops {
namespace {

namespace gx = grpc::experimental;

std::string type_name(gx::ServerRpcInfo::Type t) {
  switch (t) {
    case gx::ServerRpcInfo::Type::UNARY: return "unary";
    case gx::ServerRpcInfo::Type::CLIENT_STREAMING: return "client_stream";
    case gx::ServerRpcInfo::Type::SERVER_STREAMING: return "server_stream";
    case gx::ServerRpcInfo::Type::BIDI_STREAMING: return "bidi_stream";
  }
  return "unknown";
}

class MetricsInterceptor final : public gx::Interceptor {
 public:
  MetricsInterceptor(GrpcMetrics& metrics, gx::ServerRpcInfo* info) : metrics_(metrics), type_(type_name(info->type())) {
    // "/package.Service/Method"
    const std::string full = info->method() ? info->method() : "";
    const auto slash = full.rfind('/');
    service_ = slash == std::string::npos || slash == 0 ? "unknown" : full.substr(1, slash - 1);
    method_ = slash == std::string::npos ? full : full.substr(slash + 1);
    metrics_.started(type_, service_, method_);
  }
  ~MetricsInterceptor() override {
    const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start_).count();
    metrics_.handled(type_, service_, method_, code_, seconds);
  }
  void Intercept(gx::InterceptorBatchMethods* methods) override {
    if (methods->QueryInterceptionHookPoint(gx::InterceptionHookPoints::PRE_SEND_STATUS))
      code_ = int(methods->GetSendStatus().error_code());
    methods->Proceed();
  }

 private:
  GrpcMetrics& metrics_;
  std::string type_, service_, method_;
  int code_ = int(grpc::StatusCode::CANCELLED);  // until a status is sent
  const std::chrono::steady_clock::time_point start_ = std::chrono::steady_clock::now();
};

class Factory final : public gx::ServerInterceptorFactoryInterface {
 public:
  explicit Factory(GrpcMetrics& m) : metrics_(m) {}
  gx::Interceptor* CreateServerInterceptor(gx::ServerRpcInfo* info) override { return new MetricsInterceptor(metrics_, info); }

 private:
  GrpcMetrics& metrics_;
};

}  // namespace

std::string grpc_code_name(int code) {
  static const std::array<const char*, 17> names = {
      "OK",       "Canceled",          "Unknown",           "InvalidArgument", "DeadlineExceeded", "NotFound",
      "AlreadyExists", "PermissionDenied", "ResourceExhausted", "FailedPrecondition", "Aborted",      "OutOfRange",
      "Unimplemented", "Internal",         "Unavailable",       "DataLoss",        "Unauthenticated"};
  if (code < 0 || code >= int(names.size())) return "Code(" + std::to_string(code) + ")";
  return names[size_t(code)];
}

GrpcMetrics::GrpcMetrics(prometheus::Registry& r)
    : started_(prometheus::BuildCounter().Name("grpc_server_started_total").Help("RPCs started on the server").Register(r)),
      handled_(prometheus::BuildCounter()
                   .Name("grpc_server_handled_total")
                   .Help("RPCs completed on the server, by status code")
                   .Register(r)),
      seconds_(prometheus::BuildHistogram()
                   .Name("grpc_server_handling_seconds")
                   .Help("Time from the start of an RPC to its end on the server (a Stream call: its whole life)")
                   .Register(r)) {}

std::unique_ptr<gx::ServerInterceptorFactoryInterface> GrpcMetrics::interceptor_factory() {
  return std::make_unique<Factory>(*this);
}

void GrpcMetrics::started(const std::string& type, const std::string& service, const std::string& method) {
  started_.Add({{"grpc_type", type}, {"grpc_service", service}, {"grpc_method", method}}).Increment();
}

void GrpcMetrics::handled(const std::string& type, const std::string& service, const std::string& method, int code,
                          double seconds) {
  handled_.Add({{"grpc_type", type}, {"grpc_service", service}, {"grpc_method", method}, {"grpc_code", grpc_code_name(code)}})
      .Increment();
  seconds_
      .Add({{"grpc_type", type}, {"grpc_service", service}, {"grpc_method", method}},
           prometheus::Histogram::BucketBoundaries{0.001, 0.005, 0.01, 0.05, 0.1, 0.5, 1, 5, 10, 30, 60, 300})
      .Observe(seconds);
}

}  // namespace strata::ops
