#include "ops/ops_endpoints.h"

#include <stdexcept>

#include <prometheus/exposer.h>
#include <prometheus/registry.h>

#include "http/dashboard_hub.h"
#include "http/http_server.h"
#include "ops/frame_metrics.h"
#include "ops/grpc_metrics.h"
#include "ops/service_collector.h"
#include "ops/timed_observers.h"

namespace strata::ops {

std::pair<std::string, int> split_listen(const std::string& listen, const std::string& flag) {
  const auto colon = listen.rfind(':');
  const auto bad = [&](const std::string& why) {
    return std::invalid_argument(flag + " = '" + listen + "': " + why + " (expected host:port, e.g. 127.0.0.1:9464; port 0 picks a free one)");
  };
  if (colon == std::string::npos || colon == 0) throw bad("no host:port");
  const std::string port = listen.substr(colon + 1);
  if (port.empty() || port.size() > 5 || port.find_first_not_of("0123456789") != std::string::npos) throw bad("the port is not a number");
  const int p = std::stoi(port);
  if (p > 65535) throw bad("the port is above 65535");
  return {listen.substr(0, colon), p};
}

OpsEndpoints::OpsEndpoints(OpsOptions options) : options_(std::move(options)) {
  if (http_enabled()) split_listen(options_.http_listen, "--http");
  if (!metrics_enabled()) return;
  split_listen(options_.metrics_listen, "--metrics-listen");
  registry_ = std::make_shared<prometheus::Registry>();
  grpc_ = std::make_unique<GrpcMetrics>(*registry_);
  frames_ = std::make_shared<FrameMetrics>(*registry_);
}

OpsEndpoints::~OpsEndpoints() { stop(); }

void OpsEndpoints::stop() {
  http_.reset();
  exposer_.reset();
}

const std::string& OpsEndpoints::http_address() const {
  static const std::string none;
  return http_ ? http_->address() : none;
}

std::vector<std::unique_ptr<grpc::experimental::ServerInterceptorFactoryInterface>> OpsEndpoints::interceptors() {
  std::vector<std::unique_ptr<grpc::experimental::ServerInterceptorFactoryInterface>> out;
  if (grpc_) out.push_back(grpc_->interceptor_factory());
  return out;
}

void OpsEndpoints::attach(service::Server& server) {
  auto& observers = server.core().metrics.frame_observers;
  if (http_enabled()) hub_ = std::make_shared<http::DashboardHub>();
  if (metrics_enabled()) {  // both observers under one timer (strata_frame_observer_seconds)
    std::vector<std::shared_ptr<service::FrameObserver>> timed = {frames_};
    if (hub_) timed.push_back(hub_);
    observers.add(std::make_shared<TimedObservers>(*registry_, std::move(timed)));
  } else if (hub_) {
    observers.add(hub_);
  }
  if (http_enabled()) http_ = std::make_unique<http::HttpServer>(options_.http_listen, server.core(), hub_);
  if (!metrics_enabled()) return;
  collector_ = std::make_shared<ServiceCollector>(server.core());
  const auto [host, port] = split_listen(options_.metrics_listen, "--metrics-listen");
  try {
    exposer_ = std::make_unique<prometheus::Exposer>(options_.metrics_listen, 2);
  } catch (const std::exception& e) {
    throw std::runtime_error("--metrics-listen = '" + options_.metrics_listen + "': cannot listen (" + e.what() + ")");
  }
  exposer_->RegisterCollectable(registry_);
  exposer_->RegisterCollectable(collector_);
  const auto ports = exposer_->GetListeningPorts();
  metrics_address_ = host + ":" + std::to_string(ports.empty() ? port : ports.front());
}

}  // namespace strata::ops
