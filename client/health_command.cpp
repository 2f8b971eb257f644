// `strata health`: asks a server's grpc.health.v1 service whether it is SERVING; with --wait,
// polls until it is or the time is up (deploy scripts wait for a fresh stratad this way).
#include <chrono>
#include <iostream>
#include <memory>
#include <thread>

#include "commands.h"
#include "connection.h"
#include "connection_options.h"
#include "grpc/health/v1/health.grpc.pb.h"

namespace strata::client {
namespace {

using grpc::health::v1::HealthCheckRequest;
using grpc::health::v1::HealthCheckResponse;

struct HealthArgs {
  ConnectionOptions conn;
  std::string service;  // empty: the whole server
  double wait_s = 0.0;
};

int run_health(const HealthArgs& a) {
  auto stub = grpc::health::v1::Health::NewStub(open_channel(a.conn));
  const auto until = std::chrono::steady_clock::now() + std::chrono::milliseconds(int64_t(a.wait_s * 1000.0));
  for (;;) {
    grpc::ClientContext ctx;
    set_deadline(ctx, std::chrono::seconds(2));
    HealthCheckRequest req;
    req.set_service(a.service);
    HealthCheckResponse resp;
    const grpc::Status st = stub->Check(&ctx, req, &resp);
    const bool serving = st.ok() && resp.status() == HealthCheckResponse::SERVING;
    if (serving || std::chrono::steady_clock::now() >= until) {
      if (st.ok()) std::cout << a.conn.server << ": " << HealthCheckResponse::ServingStatus_Name(resp.status()) << "\n";
      else std::cout << a.conn.server << ": " << status_code_name(st.error_code()) << ": " << st.error_message() << "\n";
      return serving ? 0 : 1;
    }
    std::this_thread::sleep_for(std::chrono::milliseconds(100));
  }
}

}  // namespace

Runner add_health_command(CLI::App& app) {
  auto a = std::make_shared<HealthArgs>();
  auto* cmd = app.add_subcommand("health", "check a server's health (grpc.health.v1); exit 0 when SERVING");
  add_connection_flags(cmd, a->conn);
  cmd->add_option("--service", a->service, "service name (empty: the whole server)");
  cmd->add_option("--wait", a->wait_s, "seconds to keep asking until SERVING")->capture_default_str();
  return [a] { return run_health(*a); };
}

}  // namespace strata::client
