// The live dashboard of a stratad process (--http) with two sessions streaming (pt and
// restir-gather): headless Chromium (Debian's /usr/bin/chromium, or $STRATA_CHROMIUM) loads
// /dashboard with every host name resolving to nothing (uPlot must be embedded), the page logs
// nothing to the console, both sessions' six charts draw and keep updating, and a screenshot is
// written. The probes answer; a viewer that never reads holds at most the bounded queue.
#include <gtest/gtest.h>

#include <unistd.h>

#include <regex>

#include "harness.h"
#include "http/dashboard_hub.h"
#include "image/image.h"
#include "ops_util.h"

namespace strata::test {
namespace {

std::string chromium_path() { return tool_path("STRATA_CHROMIUM", "/usr/bin/chromium"); }

int run_chromium(const std::filesystem::path& dir, const std::string& args, const std::string& url, const std::filesystem::path& out,
                 const std::filesystem::path& err) {
  // --timeout stops loading after that many ms (the event stream never ends) and then dumps or shoots.
  const std::string command = "timeout 60 " + chromium_path() +
                              " --headless --no-sandbox --disable-gpu --no-first-run --no-default-browser-check"
                              " --disable-extensions --disable-background-networking --disable-sync --mute-audio"
                              " --disable-dev-shm-usage --user-data-dir=" + (dir / "profile").string() +
                              " '--host-resolver-rules=MAP * ~NOTFOUND' --enable-logging=stderr --v=0"
                              " --window-size=1400,1000 --hide-scrollbars --force-device-scale-factor=1 " + args + " '" + url +
                              "' >" + out.string() + " 2>" + err.string();
  const int status = std::system(command.c_str());
  return WIFEXITED(status) ? WEXITSTATUS(status) : -1;
}

std::vector<std::string> page_messages(const std::string& log) {
  std::vector<std::string> lines;
  std::istringstream in(log);
  for (std::string line; std::getline(in, line);)
    if (line.find(":CONSOLE") != std::string::npos || line.find("Uncaught") != std::string::npos) lines.push_back(line);
  return lines;
}

int body_attribute(const std::string& dom, const std::string& name) {
  std::smatch m;
  if (!std::regex_search(dom, m, std::regex(name + "=\"([0-9]+)\""))) return -1;
  return std::stoi(m[1].str());
}

TEST(DashboardTest, ChromiumDrawsAndUpdatesTwoSessionsWithoutConsoleOutput) {
  ASSERT_EQ(::access(chromium_path().c_str(), X_OK), 0) << chromium_path() << " is not installed (deploy/install-deps.sh)";
  TempDir dir;
  OpsDaemon daemon({"--http", "127.0.0.1:0"});
  EXPECT_EQ(http_get(daemon.http_address(), "/healthz").status, 200);
  EXPECT_EQ(http_get(daemon.http_address(), "/readyz").status, 200);

  auto stub = v1::RenderService::NewStub(loopback_channel(daemon.address()));
  const v1::Session pt = create_ok(*stub, session_request("cornell", 32, 32));
  auto restir_req = session_request("cornell", 32, 32);
  restir_req.set_method("restir-gather");
  const v1::Session restir = create_ok(*stub, restir_req);
  BackgroundStream a(daemon.address(), pt.name());
  BackgroundStream b(daemon.address(), restir.name());
  ASSERT_TRUE(wait_until([&] { return a.frames() > 0 && b.frames() > 0; }, 60s)) << "the sessions did not stream";

  const std::string url = "http://" + daemon.http_address() + "/dashboard";
  const int rc = run_chromium(dir.path, "--timeout=8000 --dump-dom", url, dir.path / "dom.html", dir.path / "dom.log");
  const std::string dom = read_text(dir.path / "dom.html");
  const std::string log = read_text(dir.path / "dom.log");
  ASSERT_EQ(rc, 0) << "chromium --dump-dom failed; log:\n" << log;
  const auto messages = page_messages(log);
  EXPECT_TRUE(messages.empty()) << "the page wrote to the console:\n" << messages.front();
  EXPECT_EQ(body_attribute(dom, "data-sessions"), 2) << dom.substr(0, 2000);
  EXPECT_EQ(body_attribute(dom, "data-charts"), 12) << "every session's six charts draw";
  EXPECT_GE(body_attribute(dom, "data-redraws"), 3) << "the charts did not update";
  EXPECT_GE(body_attribute(dom, "data-events"), 6);
  EXPECT_NE(dom.find("[live]</title>"), std::string::npos);
  EXPECT_NE(dom.find("data:image/png;base64,"), std::string::npos) << "no thumbnail";

  const auto shot = dir.path / "dashboard.png";
  const int shot_rc = run_chromium(dir.path, "--timeout=6000 --screenshot=" + shot.string(), url, dir.path / "shot.out", dir.path / "shot.log");
  ASSERT_EQ(shot_rc, 0) << read_text(dir.path / "shot.log");
  const std::string png = read_text(shot);
  ASSERT_FALSE(png.empty()) << "no screenshot";
  const image::Image img = image::decode_png(std::span(reinterpret_cast<const uint8_t*>(png.data()), png.size()));
  int coloured = 0;
  for (uint32_t y = 0; y < img.height; ++y)
    for (uint32_t x = 0; x < img.width; ++x) {
      const float* p = img.pixel(x, y);
      if (std::max({p[0], p[1], p[2]}) - std::min({p[0], p[1], p[2]}) > 0.25f) ++coloured;
    }
  EXPECT_GE(coloured, 5000) << "the screenshot shows no chart lines";
  // The screenshot stays for a person to look at when the test fails.
  if (HasFailure()) std::filesystem::copy_file(shot, std::filesystem::temp_directory_path() / "strata_dashboard_failed.png",
                                               std::filesystem::copy_options::overwrite_existing);
  EXPECT_TRUE(a.stop().ok());
  EXPECT_TRUE(b.stop().ok());
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
