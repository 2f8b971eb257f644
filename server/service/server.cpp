#include "service/server.h"

#include <algorithm>
#include <stdexcept>

#include <unistd.h>

#include <grpcpp/ext/proto_server_reflection_plugin.h>
#include <grpcpp/health_check_service_interface.h>

#include "service/auth_gate.h"
#include "service/instance_interceptor.h"
#include "service/tls_credentials.h"

namespace strata::service {
namespace {

constexpr auto k_janitor_period = std::chrono::milliseconds(100);
constexpr int k_slack_bytes = 1 << 20;

std::string host_of(const std::string& listen) {
  auto colon = listen.rfind(':');
  return colon == std::string::npos ? listen : listen.substr(0, colon);
}

// hostname-pid: unique among the daemons of one machine and readable in a proxy's logs.
std::string default_instance_id() {
  char host[256] = {};
  if (gethostname(host, sizeof host - 1) != 0) host[0] = 0;
  return std::string(host[0] ? host : "stratad") + "-" + std::to_string(getpid());
}

}  // namespace

Server::Server(const gpu::Context& ctx, ServiceConfig config,
               std::vector<std::unique_ptr<grpc::experimental::ServerInterceptorFactoryInterface>> interceptors) {
  config.validate();
  core_ = std::make_unique<ServiceCore>(ctx, std::move(config));
  const auto& cfg = core_->config;
  if (cfg.compile.progressive_start || !cfg.compile.warm_up.empty())
    core_->compiler = std::make_unique<WarmUp>(gpu::ContextOptions{cfg.compile.device, false}, cfg, cfg.compile.warm_up,
                                               cfg.compile.threads, &ctx);
  check_exposure(cfg.listen, cfg.security);  // before anything listens
  const auto credentials = server_credentials(cfg.security);
  service_ = make_render_service(*core_);  // gated by the bearer token when one is configured

  grpc::EnableDefaultHealthCheckService(true);
  grpc::reflection::InitProtoReflectionServerBuilderPlugin();
  grpc::ServerBuilder builder;
  builder.AddListeningPort(cfg.listen, credentials, &port_);
  builder.RegisterService(service_.get());
  // A CreateSession may carry an inline scene and an inline environment map.
  builder.SetMaxReceiveMessageSize(int(std::min<uint64_t>(cfg.limits.max_scene_bytes + cfg.limits.max_environment_bytes + uint64_t(k_slack_bytes), uint64_t(INT32_MAX))));
  builder.SetMaxSendMessageSize(int(max_frame_bytes(cfg.limits.max_pixels)));
  // Dead clients are noticed (and their sessions' GPU state freed) within about 30 s.
  builder.AddChannelArgument(GRPC_ARG_KEEPALIVE_TIME_MS, 20'000);
  builder.AddChannelArgument(GRPC_ARG_KEEPALIVE_TIMEOUT_MS, 10'000);
  builder.AddChannelArgument(GRPC_ARG_KEEPALIVE_PERMIT_WITHOUT_CALLS, 1);
  builder.AddChannelArgument(GRPC_ARG_HTTP2_MIN_RECV_PING_INTERVAL_WITHOUT_DATA_MS, 5'000);
  instance_id_ = cfg.instance_id.empty() ? default_instance_id() : cfg.instance_id;
  // One list of interceptors (SetInterceptorCreators replaces, it does not add): x-strata-instance
  // on every response, then the caller's (the ops metrics).
  auto all = instance_interceptors(instance_id_);
  for (auto& i : interceptors) all.push_back(std::move(i));
  builder.experimental().SetInterceptorCreators(std::move(all));
  server_ = builder.BuildAndStart();
  if (!server_ || port_ == 0) throw std::runtime_error("cannot listen on " + cfg.listen);
  address_ = host_of(cfg.listen) + ":" + std::to_string(port_);
  server_->GetHealthCheckService()->SetServingStatus(v1::RenderService::service_full_name(), true);
  server_->GetHealthCheckService()->SetServingStatus(true);
  janitor_ = std::thread([this] { janitor(); });
}

Server::~Server() { shutdown(); }

void Server::janitor() {
  std::unique_lock lock(mu_);
  while (!stopping_) {
    cv_.wait_for(lock, k_janitor_period);
    lock.unlock();
    const auto now = std::chrono::steady_clock::now();
    core_->registry.expire_idle(now);
    for (const auto& s : core_->streams.live()) s->enforce_end_deadline(now);
    lock.lock();
  }
}

void Server::drain() {
  core_->draining = true;
  server_->GetHealthCheckService()->SetServingStatus(false);
  const grpc::Status closing(grpc::StatusCode::UNAVAILABLE,
                             "stratad is draining (shutting down): the frames whose input had arrived were sent; this stream is closed");
  for (const auto& s : core_->streams.live()) s->drain(closing);
  // The janitor cancels streams still open after drain_timeout; give cancellation a moment more.
  const auto deadline = std::chrono::steady_clock::now() + core_->config.drain_timeout + std::chrono::seconds(2);
  while (core_->metrics.streams.load() > 0 && std::chrono::steady_clock::now() < deadline)
    std::this_thread::sleep_for(std::chrono::milliseconds(10));
  shutdown();
}

void Server::shutdown() {
  {
    std::lock_guard lock(mu_);
    if (stopped_) return;
    stopped_ = true;
    stopping_ = true;
  }
  cv_.notify_all();
  if (janitor_.joinable()) janitor_.join();
  core_->draining = true;
  server_->GetHealthCheckService()->SetServingStatus(false);
  server_->Shutdown(std::chrono::system_clock::now() + std::chrono::seconds(1));
  server_->Wait();
  core_->scheduler.stop();
  core_->pool.wait_idle();
}

}  // namespace strata::service
