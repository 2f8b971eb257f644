#include "http/http_server.h"

#include <map>
#include <stdexcept>
#include <vector>

#include <CivetServer.h>

#include "gpu/pipeline_warmup.h"
#include "service/auth_token.h"
#include "http/viewer_socket.h"
#include "service/tls_credentials.h"

namespace strata::http {
namespace {

constexpr auto k_keepalive = std::chrono::seconds(10);  // a comment line: notices viewers that left
constexpr int k_viewer_timeout_ms = 60'000;  // a viewer socket silent this long is closed (the page pings every 15 s)

bool send_all(mg_connection* conn, const std::string& text) { return mg_write(conn, text.data(), text.size()) == int(text.size()); }

void respond(mg_connection* conn, int status, const char* reason, const char* type, const std::string& body) {
  mg_printf(conn,
            "HTTP/1.1 %d %s\r\nContent-Type: %s\r\nContent-Length: %zu\r\nCache-Control: no-store\r\nConnection: close\r\n\r\n",
            status, reason, type, body.size());
  send_all(conn, body);
}

class PageHandler final : public CivetHandler {
 public:
  explicit PageHandler(std::string page) : page_(std::move(page)) {}
  bool handleGet(CivetServer*, mg_connection* conn) override {
    respond(conn, 200, "OK", "text/html; charset=utf-8", page_);
    return true;
  }

 private:
  const std::string page_;
};

// The dashboard's event stream: every session's frames (statistics, thumbnails). With
// --auth-token-file it needs `Authorization: Bearer <token>` (the page sends the token the viewer
// keeps for the tab, asking once on a 401); the page itself holds no data and is served to anyone.
class EventsHandler final : public CivetHandler {
 public:
  EventsHandler(std::shared_ptr<DashboardHub> hub, std::shared_ptr<const service::BearerToken> token)
      : hub_(std::move(hub)), token_(std::move(token)) {}
  bool handleGet(CivetServer*, mg_connection* conn) override {
    if (token_) {
      const char* header = mg_get_header(conn, "Authorization");
      const std::string value = header ? header : "";
      std::multimap<grpc::string_ref, grpc::string_ref> metadata;
      if (header) metadata.emplace("authorization", value);
      if (const grpc::Status st = token_->check(metadata); !st.ok()) {
        const std::string body = "/events: " + st.error_message() + "\n";
        mg_printf(conn,
                  "HTTP/1.1 401 Unauthorized\r\nWWW-Authenticate: Bearer\r\nContent-Type: text/plain\r\nContent-Length: %zu\r\n"
                  "Cache-Control: no-store\r\nConnection: close\r\n\r\n",
                  body.size());
        send_all(conn, body);
        return true;
      }
    }
    auto viewer = hub_->subscribe();
    if (!viewer) {
      respond(conn, 503, "Service Unavailable", "text/plain",
              "too many dashboard viewers (at most " + std::to_string(DashboardHub::k_max_viewers) + ")\n");
      return true;
    }
    mg_printf(conn, "HTTP/1.1 200 OK\r\nContent-Type: text/event-stream\r\nCache-Control: no-store\r\nConnection: close\r\n\r\n");
    bool ok = send_all(conn, "retry: 2000\n\n");
    auto last_write = std::chrono::steady_clock::now();
    while (ok && !viewer->closed()) {
      auto event = viewer->next(std::chrono::milliseconds(500));
      if (event) {
        ok = send_all(conn, "data: " + *event + "\n\n");
        last_write = std::chrono::steady_clock::now();
      } else if (std::chrono::steady_clock::now() - last_write >= k_keepalive) {
        ok = send_all(conn, ": keepalive\n\n");
        last_write = std::chrono::steady_clock::now();
      }
    }
    hub_->unsubscribe(viewer);
    return true;
  }

 private:
  std::shared_ptr<DashboardHub> hub_;
  const std::shared_ptr<const service::BearerToken> token_;
};

class ProbeHandler final : public CivetHandler {
 public:
  ProbeHandler(service::ServiceCore& core, bool readiness) : core_(core), readiness_(readiness) {}
  bool handleGet(CivetServer*, mg_connection* conn) override {
    const auto warm = gpu::warmup_progress();
    if (readiness_ && core_.draining.load()) respond(conn, 503, "Service Unavailable", "text/plain", "draining\n");
    else if (readiness_ && warm.running)
      respond(conn, 503, "Service Unavailable", "text/plain",
              "warming pipelines: " + std::to_string(warm.done) + " of " + std::to_string(warm.total) + " compiled\n");
    else respond(conn, 200, "OK", "text/plain", "ok\n");
    return true;
  }

 private:
  service::ServiceCore& core_;
  const bool readiness_;
};

// As service::check_exposure does for --listen. The pages are served in the clear: Debian's civetweb
// 1.15 cannot serve TLS with OpenSSL 3 (it looks up SSL_get_peer_certificate, which OpenSSL 3 no
// longer exports, and calls the null pointer on the first connection), so --tls-cert does not make
// --http safe; beyond loopback it needs the token (which the viewer's socket asks for), or a TLS
// proxy in front and --insecure.
void check_http_exposure(const std::string& listen, const service::SecurityConfig& s) {
  if (s.insecure || service::is_loopback_listen(listen) || !s.auth_token_file.empty()) return;
  throw std::invalid_argument("--http " + listen +
                              " reaches beyond loopback without a token: give --auth-token-file (the viewer's socket then asks "
                              "for it), or serve --http on loopback behind a TLS proxy, or --insecure to serve it in the clear anyway"
                              " (--http is plain HTTP even with --tls-cert)");
}

}  // namespace

HttpServer::HttpServer(const std::string& listen, service::ServiceCore& core, std::shared_ptr<DashboardHub> hub) : hub_(std::move(hub)) {
  const auto& security = core.config.security;
  check_http_exposure(listen, security);
  std::shared_ptr<const service::BearerToken> token;
  if (!security.auth_token_file.empty())
    token = std::make_shared<const service::BearerToken>(service::BearerToken::load(security.auth_token_file));
  // Enough workers for every dashboard event stream and viewer socket plus pages and probes.
  const size_t threads = DashboardHub::k_max_viewers + ViewerSocketHandler::k_max_viewers + 4;
  const std::vector<std::string> options = {"listening_ports", listen, "num_threads", std::to_string(threads),
                                            "websocket_timeout_ms", std::to_string(k_viewer_timeout_ms)};
  try {
    server_ = std::make_unique<CivetServer>(options);
  } catch (const std::exception& e) {
    throw std::runtime_error("--http = '" + listen + "': cannot listen (" + e.what() + ")");
  }
  handlers_.push_back(std::make_unique<PageHandler>(dashboard_page()));
  server_->addHandler("/dashboard", handlers_.back().get());
  handlers_.push_back(std::make_unique<PageHandler>(viewer_page()));
  server_->addHandler("/view", handlers_.back().get());
  viewers_ = std::make_unique<ViewerSocketHandler>(core, token);
  server_->addWebSocketHandler("/view/ws", viewers_.get());
  handlers_.push_back(std::make_unique<EventsHandler>(hub_, std::move(token)));
  server_->addHandler("/events", handlers_.back().get());
  handlers_.push_back(std::make_unique<ProbeHandler>(core, false));
  server_->addHandler("/healthz", handlers_.back().get());
  handlers_.push_back(std::make_unique<ProbeHandler>(core, true));
  server_->addHandler("/readyz", handlers_.back().get());
  const auto ports = server_->getListeningPorts();
  const auto colon = listen.rfind(':');
  address_ = listen.substr(0, colon) + ":" + std::to_string(ports.empty() ? 0 : ports.front());
}

HttpServer::~HttpServer() {
  hub_->close_all();  // the event streams return, so civetweb's workers can stop
  viewers_->close_all();
  server_.reset();
}

}  // namespace strata::http
