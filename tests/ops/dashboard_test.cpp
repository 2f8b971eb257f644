// The live dashboard of a stratad process (--http) with two sessions streaming (pt and
// restir-gather): headless Chromium (Debian's /usr/bin/chromium, or $STRATA_CHROMIUM) loads
// /dashboard with every host name resolving to nothing (uPlot must be embedded), the page logs
// nothing to the console, both sessions' six charts draw and keep updating, and a screenshot is
// written (driven over the DevTools pipe: the page's event stream never lets loading end). The probes answer; a viewer that never reads holds at most the bounded queue.
#include <gtest/gtest.h>

#include <unistd.h>


#include "cdp_pipe.h"
#include "harness.h"
#include "http/dashboard_hub.h"
#include "image/image.h"
#include "ops_util.h"

namespace strata::test {
namespace {

std::string chromium_path() { return tool_path("STRATA_CHROMIUM", "/usr/bin/chromium"); }

// What the page reports on <body> (dashboard.js), and its title.
struct PageState {
  int events = -1, sessions = -1, charts = -1, redraws = -1;
  std::string title;
  bool thumbnails = false;
};

PageState page_state(Chromium& browser) {
  const auto v = browser.evaluate(
      "!document.body ? '{}' : JSON.stringify({e: document.body.dataset.events, s: document.body.dataset.sessions, c: document.body.dataset.charts,"
      " r: document.body.dataset.redraws, t: document.title,"
      " th: Array.from(document.querySelectorAll('img.thumb')).filter(i => i.src.startsWith('data:image/png;base64,')).length})");
  const auto j = nlohmann::json::parse(v.get<std::string>());
  auto num = [&](const char* k) { return j.contains(k) && j[k].is_string() ? std::stoi(j[k].get<std::string>()) : -1; };
  return {num("e"), num("s"), num("c"), num("r"), j.value("t", ""), j.value("th", 0) == 2};
}

TEST(DashboardTest, ChromiumDrawsAndUpdatesTwoSessionsWithoutConsoleOutput) {
  ASSERT_EQ(::access(chromium_path().c_str(), X_OK), 0) << chromium_path() << " is not installed (deploy/install-deps.sh)";
  TempDir dir;
  OpsDaemon daemon({"--http", "127.0.0.1:0"});
  EXPECT_EQ(http_get(daemon.http_address(), "/healthz").status, 200);
  // Ready once any pipeline warm-up is done (stratad serve --warm-up).
  EXPECT_TRUE(wait_until([&] { return http_get(daemon.http_address(), "/readyz").status == 200; }, 120s));
  EXPECT_EQ(http_get(daemon.http_address(), "/nothing-here").status, 404);

  auto stub = v1::RenderService::NewStub(loopback_channel(daemon.address()));
  const v1::Session pt = create_ok(*stub, session_request("cornell", 32, 32));
  auto restir_req = session_request("cornell", 32, 32);
  restir_req.set_method("restir-gather");
  const v1::Session restir = create_ok(*stub, restir_req);
  BackgroundStream a(daemon.address(), pt.name());
  BackgroundStream b(daemon.address(), restir.name());
  ASSERT_TRUE(wait_until([&] { return a.frames() > 0 && b.frames() > 0; }, 60s)) << "the sessions did not stream";

  Chromium browser(chromium_path(), dir.path, 1400, 1000);
  browser.open("http://" + daemon.http_address() + "/dashboard");
  // Both sessions' six charts drawn, thumbnails shown.
  PageState first;
  const bool drawn = wait_until([&] {
    first = page_state(browser);
    return first.sessions == 2 && first.charts == 12 && first.thumbnails && first.title.ends_with("[live]");
  }, 30s);
  EXPECT_TRUE(drawn) << "sessions " << first.sessions << ", charts " << first.charts << ", title '" << first.title << "'\n"
                     << browser.log();
  // And they keep updating as frames arrive.
  PageState later;
  EXPECT_TRUE(wait_until([&] {
    later = page_state(browser);
    return later.events >= first.events + 4 && later.redraws > first.redraws;
  }, 20s)) << "events " << first.events << " -> " << later.events << ", redraws " << first.redraws << " -> " << later.redraws;
  for (const auto& m : browser.page_messages()) ADD_FAILURE() << "the page wrote to the console: " << m;

  const std::string png = browser.screenshot_png();
  write_text(dir.path / "dashboard.png", png);
  const image::Image img = image::decode_png(std::span(reinterpret_cast<const uint8_t*>(png.data()), png.size()));
  EXPECT_EQ(img.width, 1400u);
  int coloured = 0;
  for (uint32_t y = 0; y < img.height; ++y)
    for (uint32_t x = 0; x < img.width; ++x) {
      const float* p = img.pixel(x, y);
      if (std::max({p[0], p[1], p[2]}) - std::min({p[0], p[1], p[2]}) > 0.25f) ++coloured;
    }
  EXPECT_GE(coloured, 5000) << "the screenshot shows no chart lines";
  // The screenshot is kept where a person can look at it.
  const auto kept = std::filesystem::temp_directory_path() / "strata_dashboard.png";
  std::filesystem::copy_file(dir.path / "dashboard.png", kept, std::filesystem::copy_options::overwrite_existing);
  std::printf("dashboard: %d events, %d redraws, screenshot %s (%d coloured pixels)\n", later.events, later.redraws,
              kept.c_str(), coloured);
  EXPECT_TRUE(a.stop().ok());
  EXPECT_TRUE(b.stop().ok());
}

// With --auth-token-file the event stream (every session's statistics and thumbnails) needs the
// token, as the viewer's socket does; the page, which holds no data, does not. Chromium's page asks
// for the token on the 401 and goes live with it.
TEST(DashboardTest, TheEventStreamNeedsTheTokenWhereTheDaemonHasOne) {
  ASSERT_EQ(::access(chromium_path().c_str(), X_OK), 0) << chromium_path() << " is not installed (deploy/install-deps.sh)";
  TempDir dir;
  const std::string token = "dashboard-test-token-0123456789";
  write_text(dir.path / "token", token + "\n");
  OpsDaemon daemon({"--http", "127.0.0.1:0", "--auth-token-file", (dir.path / "token").string()});
  EXPECT_EQ(http_get(daemon.http_address(), "/dashboard").status, 200);
  const HttpResponse none = http_get(daemon.http_address(), "/events", 3s);
  EXPECT_EQ(none.status, 401) << none.headers;
  EXPECT_NE(none.headers.find("WWW-Authenticate: Bearer"), std::string::npos) << none.headers;
  EXPECT_NE(none.body.find("token"), std::string::npos) << none.body;
  const HttpResponse wrong = http_get(daemon.http_address(), "/events", 3s, "Authorization: Bearer not-the-token-at-all\r\n");
  EXPECT_EQ(wrong.status, 401) << wrong.headers;
  EXPECT_EQ(wrong.body.find(token), std::string::npos);
  const HttpResponse right = http_get(daemon.http_address(), "/events", 1500ms, "Authorization: Bearer " + token + "\r\n");
  EXPECT_EQ(right.status, 200) << right.headers;
  EXPECT_TRUE(right.body.starts_with("retry:")) << right.body;

  Chromium browser(chromium_path(), dir.path, 800, 600);
  browser.open("http://" + daemon.http_address() + "/dashboard");
  auto text = [&](const std::string& js) { return browser.evaluate(js).get<std::string>(); };
  const std::string form_shown = "document.getElementById('token-form') ? getComputedStyle(document.getElementById('token-form')).display : ''";
  const std::string status = "document.getElementById('status') ? document.getElementById('status').textContent : ''";
  // (a flex item: its computed display is block, not the inline the page sets)
  EXPECT_TRUE(wait_until([&] { return text(form_shown) == "block"; }, 20s)) << text(status) << ", form display " << text(form_shown);
  browser.evaluate("document.getElementById('token').value = '" + token + "', document.getElementById('token-form').requestSubmit(), true");
  EXPECT_TRUE(wait_until([&] { return text(status) == "live"; }, 20s)) << text(status);
  EXPECT_EQ(text(form_shown), "none");
}

TEST(DashboardTest, ASlowViewerDropsEventsInsteadOfQueueing) {
  http::DashboardHub hub;
  auto slow = hub.subscribe();
  auto fast = hub.subscribe();
  ASSERT_TRUE(slow && fast);
  for (int i = 0; i < 1000; ++i) {
    hub.publish("{\"n\":" + std::to_string(i) + "}");
    ASSERT_TRUE(fast->next(std::chrono::milliseconds(0)).has_value());
  }
  EXPECT_EQ(slow->dropped(), 1000 - http::DashboardHub::k_queue_limit);
  EXPECT_EQ(fast->dropped(), 0u);
  // What is left is the newest k_queue_limit events, oldest first.
  EXPECT_EQ(*slow->next(std::chrono::milliseconds(0)), "{\"n\":" + std::to_string(1000 - http::DashboardHub::k_queue_limit) + "}");
  size_t left = 1;
  while (slow->next(std::chrono::milliseconds(0))) ++left;
  EXPECT_EQ(left, http::DashboardHub::k_queue_limit);
  // Viewers are bounded too.
  std::vector<std::shared_ptr<http::DashboardHub::Viewer>> more;
  while (auto v = hub.subscribe()) more.push_back(v);
  EXPECT_EQ(hub.viewers(), http::DashboardHub::k_max_viewers);
  hub.close_all();
  EXPECT_FALSE(slow->next(std::chrono::milliseconds(0)).has_value());
}

}  // namespace
}  // namespace strata::test
