#pragma once
// `stratad serve --http host:port`: the live dashboard and the probes, on civetweb.
//   /dashboard  one self-contained page (uPlot embedded at build time; no network at view time)
//   /events     server-sent events, one per rendered frame (DashboardHub: bounded per viewer)
//   /healthz    200 while the process serves HTTP at all (liveness)
//   /readyz     200 while the service takes new sessions and its pipelines are warm, 503 while
//               they compile or once it drains (readiness)
//   /view       the live viewer: one page (viewer_page.cpp) whose socket /view/ws opens a session
//               through the service core (viewer_stream.h)
// With --auth-token-file the viewer's socket asks for the token; beyond loopback the token is
// required (the pages are plain HTTP: see check_http_exposure in http_server.cpp).
#include <memory>
#include <string>

#include "http/dashboard_hub.h"
#include "service/service_core.h"

class CivetServer;
class CivetHandler;

namespace strata::http {
class ViewerSocketHandler;
}

namespace strata::http {

class HttpServer {
 public:
  // Listens on `listen` (port 0: a free one); throws std::runtime_error naming --http when it cannot.
  HttpServer(const std::string& listen, service::ServiceCore& core, std::shared_ptr<DashboardHub> hub);
  ~HttpServer();  // closes the event streams, then stops
  HttpServer(const HttpServer&) = delete;
  HttpServer& operator=(const HttpServer&) = delete;
  const std::string& address() const { return address_; }

 private:
  std::shared_ptr<DashboardHub> hub_;
  std::unique_ptr<CivetServer> server_;
  std::vector<std::unique_ptr<CivetHandler>> handlers_;
  std::unique_ptr<ViewerSocketHandler> viewers_;
  std::string address_;
};

// The dashboard page: HTML with uPlot, its stylesheet and the page's script inlined.
std::string dashboard_page();
// The viewer page: HTML with uPlot, its stylesheet and the page's script inlined.
std::string viewer_page();

}  // namespace strata::http
