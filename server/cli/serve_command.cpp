// `stratad serve`: the render service over gRPC on one device, until SIGTERM or SIGINT, which
// drain it gracefully (health NOT_SERVING, new work refused, frames in flight finished, exit 0).
#include <csignal>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <memory>

#include <pthread.h>

#include <algorithm>
#include <thread>

#include "cli/commands.h"
#include "gpu/context.h"
#include "ops/ops_endpoints.h"
#include "service/server.h"
#include "service/warm_up.h"

namespace strata::cli {
namespace {

struct ServeArgs {
  service::ServiceConfig config;
  double idle_timeout_s = 300.0;
  double drain_timeout_s = 10.0;
  std::string port_file;
  std::string device;
  bool validation = false;
  ops::OpsOptions ops;  // --metrics-listen, --http
  // Off by default: at start it compiles every pipeline of the methods named, also those the first
  // frame does not need, before any session asks for them (docs/BENCHMARKS.md).
  std::string warm_up = "none";
  unsigned warm_up_threads = std::max(1u, std::thread::hardware_concurrency());
  bool progressive_start = true;
};

void write_port_file(const std::string& path, int port) {
  const std::string tmp = path + ".tmp";
  {
    std::ofstream out(tmp);
    out << port << "\n";
    if (!out) throw std::runtime_error("cannot write the port file " + tmp);
  }
  std::filesystem::rename(tmp, path);
}

int run_serve(ServeArgs& a) {
  // Every thread started from here on inherits the blocked signals; this one waits for them.
  sigset_t signals;
  sigemptyset(&signals);
  sigaddset(&signals, SIGTERM);
  sigaddset(&signals, SIGINT);
  pthread_sigmask(SIG_BLOCK, &signals, nullptr);

  a.config.idle_timeout = std::chrono::milliseconds(int64_t(a.idle_timeout_s * 1000.0));
  a.config.drain_timeout = std::chrono::milliseconds(int64_t(a.drain_timeout_s * 1000.0));
  a.config.validate();
  // The validation layer would report the compiling devices' dispatches without resources bound:
  // neither the warm-up nor the progressive start then.
  a.config.compile = {a.device, a.validation ? std::vector<std::string>{} : service::parse_warm_up(a.warm_up),
                      a.warm_up_threads, a.progressive_start && !a.validation};
  ops::OpsEndpoints ops(a.ops);  // before the server: its interceptor sees every call; destroyed after it
  gpu::Context ctx({a.device, a.validation});
  // The warm-up starts in the server's constructor, before the addresses are printed, so that
  // /readyz answers 503 from its first request.
  service::Server server(ctx, a.config, ops.interceptors());
  ops.attach(server);
  if (!a.port_file.empty()) write_port_file(a.port_file, server.port());
  std::cout << "stratad: serving strata.v1.RenderService on " << server.address() << " (device: " << ctx.device_name()
            << "; instance " << server.instance_id() << (a.config.security.tls_cert.empty() ? "" : "; TLS")
            << (a.config.security.tls_client_ca.empty() ? "" : " with client certificates")
            << (a.config.security.auth_token_file.empty() ? "" : "; bearer token") << ")" << std::endl;
  if (ops.metrics_enabled()) std::cout << "stratad: metrics on http://" << ops.metrics_address() << "/metrics" << std::endl;
  if (ops.http_enabled()) {
    std::cout << "stratad: dashboard on http://" << ops.http_address() << "/dashboard" << std::endl;
    std::cout << "stratad: viewer on http://" << ops.http_address() << "/view" << std::endl;
  }


  int sig = 0;
  sigwait(&signals, &sig);
  std::cout << "stratad: " << strsignal(sig) << ": draining" << std::endl;
  server.drain();
  ops.stop();  // the pages read the service: they stop before it goes
  // A compile in progress cannot be cut short (LLVM); the service waits for it as it goes, so that
  // its code reaches Mesa's cache. Say so, and let a second signal end the process at once.
  const auto* compiler = server.core().compiler.get();
  if (compiler && compiler->busy()) {
    std::cout << "stratad: waiting for the pipeline compile in progress (its code goes to Mesa's cache; up to a minute or "
                 "two on a cold cache): send SIGTERM or SIGINT again to exit now"
              << std::endl;
    std::thread([signals] {
      int again = 0;
      sigwait(&signals, &again);
      std::cout << "stratad: " << strsignal(again) << ": exiting without waiting for the compile" << std::endl;
      std::_Exit(0);
    }).detach();
  }
  std::cout << "stratad: stopped" << std::endl;
  return 0;
}

}  // namespace

Runner add_serve_command(CLI::App& app) {
  auto a = std::make_shared<ServeArgs>();
  auto& c = a->config;
  auto& l = c.limits;
  auto* cmd = app.add_subcommand("serve", "serve strata.v1.RenderService over gRPC until SIGTERM (graceful drain)");
  cmd->add_option("--listen", c.listen, "host:port to listen on; port 0 picks a free one")->capture_default_str();
  cmd->add_option("--port-file", a->port_file, "write the port actually bound to this file once serving");
  cmd->add_option("--scene-dir", c.scene_dir, "directory that SceneSource.path may load .gltf/.glb files from");
  cmd->add_option("--max-sessions", l.max_sessions, "open sessions at once")->capture_default_str();
  cmd->add_option("--max-pixels", l.max_pixels, "width * height of one session")->capture_default_str();
  cmd->add_option("--max-dimension", l.max_dimension, "width and height each")->capture_default_str();
  cmd->add_option("--max-scene-bytes", l.max_scene_bytes, "inline .glb and scene files")->capture_default_str();
  cmd->add_option("--max-texture-bytes", l.max_texture_bytes, "a scene's decoded textures (RGBA8 with mip levels)")->capture_default_str();
  cmd->add_option("--max-instances", l.max_instances, "instances of one scene")->capture_default_str();
  cmd->add_option("--max-spp", l.max_spp, "samples per pixel per frame")->capture_default_str();
  cmd->add_option("--max-depth", l.max_depth, "path segments")->capture_default_str();
  cmd->add_option("--idle-timeout", a->idle_timeout_s, "seconds after which a session without a stream expires")->capture_default_str();
  cmd->add_option("--drain-timeout", a->drain_timeout_s, "seconds that SIGTERM waits for frames in flight")->capture_default_str();
  cmd->add_option("--encode-threads", c.encode_threads, "threads encoding frames")->capture_default_str();
  cmd->add_option("--max-reference-spp", l.max_reference_spp, "RenderReference: target samples per pixel")->capture_default_str();
  cmd->add_option("--max-environment-bytes", l.max_environment_bytes, "an environment map file (SceneSource.environment)")->capture_default_str();
  cmd->add_option("--max-environment-dimension", l.max_environment_dimension, "an environment map's width and height each, in texels")
      ->capture_default_str();
  cmd->add_option("--reference-cache", c.reference_cache,
                  "directory of cached references (default: $XDG_CACHE_HOME/strata/references, else ~/.cache/strata/references)");
  cmd->add_option("--device", a->device, "Vulkan device name substring (default: $STRATA_DEVICE, else lavapipe)");
  cmd->add_flag("--validation", a->validation, "enable the Khronos validation layer");
  cmd->add_option("--warm-up", a->warm_up,
                  "methods whose pipelines are compiled at start, in parallel (comma-separated, e.g. restir-gather, or all, or none); /readyz is 503 meanwhile")
      ->capture_default_str();
  cmd->add_option("--warm-up-threads", a->warm_up_threads, "devices compiling pipelines in parallel (at start, and for a progressive start)")
      ->capture_default_str();
  cmd->add_flag("--progressive-start,!--no-progressive-start", a->progressive_start,
                "a session whose method's pipelines are not compiled yet renders with pt while they compile in the "
                "background, and with its method from the frame after (frames say so); off: its first frame waits for "
                "the compile (on by default)");
  cmd->add_option("--metrics-listen", a->ops.metrics_listen, "host:port of the Prometheus /metrics page (e.g. 127.0.0.1:9464; off when not given)");
  cmd->add_option("--http", a->ops.http_listen, "host:port of the live dashboard (/dashboard, /events), the viewer (/view) and probes (/healthz, /readyz); off when not given");
  // Scale-out and security (deploy/, service/auth_gate.h, service/tls_credentials.h).
  auto& sec = c.security;
  cmd->add_option("--instance-id", c.instance_id, "sent as x-strata-instance on every response (default: hostname-pid)");
  cmd->add_option("--tls-cert", sec.tls_cert, "PEM certificate chain: serve over TLS (with --tls-key)");
  cmd->add_option("--tls-key", sec.tls_key, "PEM private key of --tls-cert");
  cmd->add_option("--tls-client-ca", sec.tls_client_ca, "PEM CA: require client certificates it signed (mutual TLS)");
  cmd->add_option("--auth-token-file", sec.auth_token_file, "file holding the token every call must send as 'authorization: Bearer <token>'");
  cmd->add_flag("--insecure", sec.insecure, "allow listening beyond loopback without TLS or a token");
  return [a] { return run_serve(*a); };
}

}  // namespace strata::cli
