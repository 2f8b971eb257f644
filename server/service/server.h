#pragma once
// `stratad serve` as a library: the gRPC server with strata.v1.RenderService, grpc.health.v1
// health checking and server reflection, message size limits raised to the largest frame, idle
// expiry, and graceful drain.
#include <condition_variable>
#include <memory>
#include <mutex>
#include <string>
#include <thread>
#include <vector>

#include <grpcpp/grpcpp.h>
#include <grpcpp/support/server_interceptor.h>

#include "gpu/context.h"
#include "service/config.h"
#include "service/render_service.h"
#include "service/service_core.h"

namespace strata::service {

class Server {
 public:
  // Listens on config.listen (port 0: a free port) and serves until drain() or destruction.
  // Throws std::invalid_argument for a bad configuration, std::runtime_error when it cannot listen.
  // `interceptors` see every call (the metrics exporter's, server/ops).
  Server(const gpu::Context& ctx, ServiceConfig config,
         std::vector<std::unique_ptr<grpc::experimental::ServerInterceptorFactoryInterface>> interceptors = {});
  ~Server();
  Server(const Server&) = delete;
  Server& operator=(const Server&) = delete;

  const std::string& address() const { return address_; }  // host:port actually bound
  int port() const { return port_; }
  const std::string& instance_id() const { return instance_id_; }  // x-strata-instance of every response
  ServiceCore& core() { return *core_; }

  // Graceful drain (SIGTERM): health NOT_SERVING; new sessions and streams refused with
  // UNAVAILABLE; the frames whose input already arrived are rendered and sent (for at most
  // drain_timeout, then the streams are cancelled); streams end with UNAVAILABLE; the server stops.
  void drain();
  // Stops at once: streams are cancelled.
  void shutdown();

 private:
  void janitor();
  std::unique_ptr<ServiceCore> core_;
  std::unique_ptr<RenderServiceImpl> service_;
  std::unique_ptr<grpc::Server> server_;
  std::string address_;
  std::string instance_id_;
  int port_ = 0;
  std::mutex mu_;
  std::condition_variable cv_;
  bool stopping_ = false;
  bool stopped_ = false;
  std::thread janitor_;
};

}  // namespace strata::service
