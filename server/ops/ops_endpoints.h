#pragma once
// The operations side of `stratad serve`, kept apart from the render service: the Prometheus
// /metrics page (--metrics-listen), the gRPC interceptor and frame observer that feed it, and the
// live dashboard with the health probes (--http).
// Built before the Server (the interceptor must be in place when the server starts), attached to
// it after (the collectors read its ServiceCore); it must outlive the Server's calls, so it is
// destroyed after the Server.
#include <memory>
#include <string>
#include <vector>

#include <grpcpp/support/server_interceptor.h>

#include "service/server.h"

namespace prometheus {
class Exposer;
class Registry;
}  // namespace prometheus

namespace strata::http {
class DashboardHub;
class HttpServer;
}  // namespace strata::http

namespace strata::ops {

class FrameMetrics;
class GrpcMetrics;
class ServiceCollector;

struct OpsOptions {
  std::string metrics_listen;  // host:port of /metrics; empty: no metrics endpoint
  std::string http_listen;     // host:port of /dashboard, /events, /healthz, /readyz; empty: none
};

class OpsEndpoints {
 public:
  explicit OpsEndpoints(OpsOptions options);
  ~OpsEndpoints();
  OpsEndpoints(const OpsEndpoints&) = delete;
  OpsEndpoints& operator=(const OpsEndpoints&) = delete;

  bool metrics_enabled() const { return !options_.metrics_listen.empty(); }
  // For Server's constructor: empty when metrics are off (no per-call cost then).
  std::vector<std::unique_ptr<grpc::experimental::ServerInterceptorFactoryInterface>> interceptors();
  // Starts listening; throws std::runtime_error naming the flag when the address cannot be bound.
  void attach(service::Server& server);
  // Stops serving /metrics and the dashboard (they read the Server's state: call it before the
  // Server goes). Idempotent; the destructor calls it too.
  void stop();
  // host:port actually bound (port 0 picks a free one); empty when off.
  const std::string& metrics_address() const { return metrics_address_; }
  bool http_enabled() const { return !options_.http_listen.empty(); }
  const std::string& http_address() const;

 private:
  OpsOptions options_;
  std::shared_ptr<prometheus::Registry> registry_;
  std::unique_ptr<GrpcMetrics> grpc_;
  std::shared_ptr<FrameMetrics> frames_;
  std::shared_ptr<ServiceCollector> collector_;
  std::unique_ptr<prometheus::Exposer> exposer_;
  std::string metrics_address_;
  std::shared_ptr<http::DashboardHub> hub_;
  std::unique_ptr<http::HttpServer> http_;
};

// "host:port" split at the last colon; throws std::invalid_argument naming `flag` when malformed.
std::pair<std::string, int> split_listen(const std::string& listen, const std::string& flag);

}  // namespace strata::ops
