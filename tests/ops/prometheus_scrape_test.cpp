// deploy/: the scrape config and the recording rules pass promtool, and Debian's Prometheus, on
// loopback scraping a live stratad (two sessions streaming, pt and restir-gather) every second
// with deploy/prometheus/strata_rules.yml, answers every query of the Grafana dashboard
// (deploy/grafana/stratad-dashboard.json) with data.
#include <gtest/gtest.h>

#include <arpa/inet.h>
#include <netinet/in.h>
#include <sys/socket.h>
#include <unistd.h>

#include <nlohmann/json.hpp>

#include "harness.h"
#include "ops_util.h"

namespace strata::test {
namespace {

const std::filesystem::path k_deploy = std::filesystem::path(STRATA_SOURCE_DIR) / "deploy";

// A port that was free a moment ago (Prometheus cannot report the one it bound).
int free_port() {
  const int fd = ::socket(AF_INET, SOCK_STREAM, 0);
  sockaddr_in addr{};
  addr.sin_family = AF_INET;
  addr.sin_addr.s_addr = htonl(INADDR_LOOPBACK);
  addr.sin_port = 0;
  ::bind(fd, reinterpret_cast<sockaddr*>(&addr), sizeof addr);
  socklen_t len = sizeof addr;
  ::getsockname(fd, reinterpret_cast<sockaddr*>(&addr), &len);
  ::close(fd);
  return ntohs(addr.sin_port);
}

std::string url_encode(const std::string& s) {
  static const char* hex = "0123456789ABCDEF";
  std::string out;
  for (unsigned char c : s) {
    if (std::isalnum(c) || c == '-' || c == '_' || c == '.' || c == '~') out += char(c);
    else {
      out += '%';
      out += hex[c >> 4];
      out += hex[c & 15];
    }
  }
  return out;
}

TEST(PrometheusScrapeTest, DeployFilesPassPromtool) {
  const std::string promtool = tool_path("STRATA_PROMTOOL", "/usr/bin/promtool");
  const auto config = run_process({promtool, "check", "config", (k_deploy / "prometheus/prometheus.yml").string()}, 60s);
  EXPECT_EQ(config.exit_code, 0) << config.output;
  const auto rules = run_process({promtool, "check", "rules", (k_deploy / "prometheus/strata_rules.yml").string()}, 60s);
  EXPECT_EQ(rules.exit_code, 0) << rules.output;
}

TEST(PrometheusScrapeTest, EveryGrafanaPanelQueryReturnsData) {
  TempDir dir;
  OpsDaemon daemon({"--metrics-listen", "127.0.0.1:0"});
  auto stub = v1::RenderService::NewStub(loopback_channel(daemon.address()));
  const v1::Session pt = create_ok(*stub, session_request("cornell", 16, 16));
  auto restir_req = session_request("cornell", 16, 16);
  restir_req.set_method("restir-gather");
  const v1::Session restir = create_ok(*stub, restir_req);
  BackgroundStream a(daemon.address(), pt.name());
  BackgroundStream b(daemon.address(), restir.name());

  // The deploy config with the daemon's address, a 1 s interval and the rules file by path.
  const int port = free_port();
  const std::string prom_address = "127.0.0.1:" + std::to_string(port);
  write_text(dir.path / "prometheus.yml", "global:\n  scrape_interval: 1s\n  evaluation_interval: 1s\nrule_files:\n  - " +
                                              (k_deploy / "prometheus/strata_rules.yml").string() +
                                              "\nscrape_configs:\n  - job_name: stratad\n    static_configs:\n      - targets: [\"" +
                                              daemon.metrics_address() + "\"]\n");
  Process prometheus({tool_path("STRATA_PROMETHEUS", "/usr/bin/prometheus"), "--config.file=" + (dir.path / "prometheus.yml").string(),
                      "--storage.tsdb.path=" + (dir.path / "data").string(), "--web.listen-address=" + prom_address,
                      "--storage.tsdb.retention.time=1h"});
  auto query = [&](const std::string& expr) {
    const HttpResponse r = http_get(prom_address, "/api/v1/query?query=" + url_encode(expr), 5s);
    if (r.status != 200) return nlohmann::json();
    return nlohmann::json::parse(r.body, nullptr, false);
  };
  auto has_data = [&](const std::string& expr) {
    const auto j = query(expr);
    return j.is_object() && j.value("status", "") == "success" && !j["data"]["result"].empty();
  };
  // Up, and enough scrapes for rate() over the windows the panels use (two samples at least).
  ASSERT_TRUE(wait_until([&] { return has_data("count_over_time(up{job=\"stratad\"}[1m]) >= 4"); }, 60s))
      << "Prometheus did not scrape stratad:\n" << prometheus.output();
  EXPECT_TRUE(has_data("up{job=\"stratad\"} == 1"));

  const auto dashboard = nlohmann::json::parse(read_text(k_deploy / "grafana/stratad-dashboard.json"));
  int queries = 0;
  for (const auto& panel : dashboard["panels"]) {
    for (const auto& target : panel["targets"]) {
      const std::string expr = target["expr"];
      ++queries;
      // Recording rules are evaluated every second; give each query a few seconds.
      EXPECT_TRUE(wait_until([&] { return has_data(expr); }, 10s)) << "panel '" << panel["title"] << "': no data for " << expr
                                                                  << "\n" << query(expr).dump();
    }
  }
  EXPECT_GE(queries, 12);
  EXPECT_TRUE(a.stop().ok());
  EXPECT_TRUE(b.stop().ok());
}

}  // namespace
}  // namespace strata::test
