// report.html in headless Chromium (Debian's /usr/bin/chromium, or $STRATA_CHROMIUM): a synthetic
// report (2 scenes, 3 runs, 8 frames, disoccluded-pixel errors, insets) must load with no console
// output at all (the page logs nothing on success, so any CONSOLE line is an error or a stray
// log), draw all 24 plots (data-plots and the "[ready]" title) with every host name resolving to
// nothing (so a page that needed the network would miss uPlot and fail), and show the three runs'
// lines in every plot area that lies inside a 1400x3000 screenshot.
#include <gtest/gtest.h>

#include <array>
#include <chrono>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <regex>
#include <sstream>
#include <string>
#include <unistd.h>
#include <vector>

#include <nlohmann/json.hpp>

#include "image/image.h"
#include "report/report.h"
#include "synthetic.h"

namespace strata::report {
namespace {

constexpr int kWidth = 1400, kHeight = 3000;
constexpr int kExpectedPlots = 2 /*scenes*/ * 2 /*whole, masked*/ * 2 /*x axes*/ * 3 /*metrics*/;

std::string read_file(const std::filesystem::path& path) {
  std::ifstream in(path, std::ios::binary);
  return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

std::string chromium_path() {
  const char* env = std::getenv("STRATA_CHROMIUM");
  return env && *env ? env : "/usr/bin/chromium";
}

// Runs headless Chromium on `url` with `args`; stdout and stderr go to the given files.
int run_chromium(const std::filesystem::path& dir, const std::string& args, const std::string& url,
                 const std::filesystem::path& out, const std::filesystem::path& err) {
  const std::string command =
      "timeout 90 " + chromium_path() +
      " --headless --no-sandbox --disable-gpu --no-first-run --no-default-browser-check"
      " --disable-extensions --disable-background-networking --disable-sync --mute-audio"
      " --disable-dev-shm-usage --user-data-dir=" + (dir / "profile").string() +
      " '--host-resolver-rules=MAP * ~NOTFOUND' --enable-logging=stderr --v=0 " + args + " '" + url +
      "' >" + out.string() + " 2>" + err.string();
  const int status = std::system(command.c_str());
  return WIFEXITED(status) ? WEXITSTATUS(status) : -1;
}

// Lines of Chromium's log that come from the page: console messages and uncaught exceptions.
std::vector<std::string> page_messages(const std::string& log) {
  std::vector<std::string> lines;
  std::istringstream in(log);
  for (std::string line; std::getline(in, line);) {
    if (line.find(":CONSOLE") != std::string::npos || line.find("Uncaught") != std::string::npos) {
      lines.push_back(line);
    }
  }
  return lines;
}

struct Rgb {
  int r, g, b;
};

Rgb pixel(const image::Image& img, int x, int y) {
  const float* p = img.pixel(uint32_t(x), uint32_t(y));
  return {int(p[0] * 255.0f + 0.5f), int(p[1] * 255.0f + 0.5f), int(p[2] * 255.0f + 0.5f)};
}

// The series colours of the three runs (web/report.js's first three RUN_COLORS).
constexpr std::array<Rgb, 3> kSeriesColours = {{{0x1f, 0x77, 0xb4}, {0xd6, 0x27, 0x28}, {0x2c, 0xa0, 0x2c}}};

// Writes `report` as report.html into a fresh directory and loads it with --dump-dom in the
// window the screenshot uses (so that the plot rectangles the page reports are where the
// screenshot has them): no console output, `expected_plots` drawn, the "[ready]" title. The plot
// rectangles go to `rects`.
struct Page {
  std::filesystem::path dir;
  std::string url;
  std::string window = "--hide-scrollbars --force-device-scale-factor=1 --virtual-time-budget=10000 --window-size=" +
                       std::to_string(kWidth) + "," + std::to_string(kHeight);
};

void load_page(const Report& report, const std::string& name, int expected_plots, Page& page, nlohmann::json& rects) {
  ASSERT_EQ(::access(chromium_path().c_str(), X_OK), 0)
      << chromium_path() << " is not installed (deploy/install-deps.sh installs Debian's chromium)";
  page.dir = std::filesystem::temp_directory_path() /
             ("strata_report_browser_" + name + "_" + std::to_string(::getpid()));
  std::filesystem::remove_all(page.dir);
  std::filesystem::create_directories(page.dir);
  write_html(report, page.dir / "report.html");
  page.url = "file://" + (page.dir / "report.html").string();

  const int rc = run_chromium(page.dir, page.window + " --dump-dom", page.url, page.dir / "dom.html", page.dir / "dom.log");
  const std::string dom = read_file(page.dir / "dom.html");
  const std::string log = read_file(page.dir / "dom.log");
  ASSERT_EQ(rc, 0) << "chromium --dump-dom failed; log:\n" << log;
  const auto messages = page_messages(log);
  EXPECT_TRUE(messages.empty()) << "the page wrote to the console:\n" << messages.front();
  EXPECT_NE(dom.find("data-plots=\"" + std::to_string(expected_plots) + "\""), std::string::npos)
      << "the page did not report " << expected_plots << " plots drawn";
  std::smatch title;
  ASSERT_TRUE(std::regex_search(dom, title, std::regex("<title>([^<]*)</title>")));
  EXPECT_TRUE(title[1].str().ends_with("[ready]")) << "title: " << title[1];
  std::smatch rects_attr;
  ASSERT_TRUE(std::regex_search(dom, rects_attr, std::regex("data-plot-rects=\"([^\"]*)\"")))
      << "no data-plot-rects on <body>";
  rects = nlohmann::json::parse(rects_attr[1].str());
  ASSERT_EQ(rects.size(), size_t(expected_plots));
}

TEST(ReportBrowser, ChromiumDrawsEveryPlotWithoutConsoleOutput) {
  const auto start = std::chrono::steady_clock::now();
  const Report report = testing::synthetic_report({.scenes = 2, .frames = 8, .masked = true, .insets = true});
  Page page;
  nlohmann::json rects;
  ASSERT_NO_FATAL_FAILURE(load_page(report, "full", kExpectedPlots, page, rects));
  const auto& dir = page.dir;

  // 2. A screenshot: every plot area that lies inside it must show the three runs' lines.
  const auto shot = dir / "report.png";
  const int shot_rc =
      run_chromium(dir, page.window + " --screenshot=" + shot.string(), page.url, dir / "shot.out", dir / "shot.log");
  ASSERT_EQ(shot_rc, 0) << "chromium --screenshot failed; log:\n" << read_file(dir / "shot.log");
  const std::string png = read_file(shot);
  const image::Image img = image::decode_png(std::span(reinterpret_cast<const uint8_t*>(png.data()), png.size()));
  ASSERT_EQ(img.width, uint32_t(kWidth));
  ASSERT_EQ(img.height, uint32_t(kHeight));

  int visible = 0;
  int least_coloured = -1, least_series = -1;
  for (const auto& rect : rects) {
    const int x0 = rect[0], y0 = rect[1], w = rect[2], h = rect[3];
    EXPECT_GE(w, 250);
    EXPECT_GE(h, 100);
    if (x0 < 0 || y0 < 0 || x0 + w > kWidth || y0 + h > kHeight) continue;
    ++visible;
    // "Coloured": far from grey (the background, grid and axes are white or grey).
    int coloured = 0;
    std::array<int, 3> per_series{};
    for (int y = y0; y < y0 + h; ++y) {
      for (int x = x0; x < x0 + w; ++x) {
        const Rgb c = pixel(img, x, y);
        if (std::max({c.r, c.g, c.b}) - std::min({c.r, c.g, c.b}) >= 60) ++coloured;
        for (size_t s = 0; s < kSeriesColours.size(); ++s) {
          const Rgb& k = kSeriesColours[s];
          if (std::abs(c.r - k.r) <= 24 && std::abs(c.g - k.g) <= 24 && std::abs(c.b - k.b) <= 24) ++per_series[s];
        }
      }
    }
    if (least_coloured < 0 || coloured < least_coloured) least_coloured = coloured;
    for (const int n : per_series) least_series = least_series < 0 ? n : std::min(least_series, n);
    EXPECT_GE(coloured, 600) << "plot at " << rect.dump() << " looks empty";
    for (size_t s = 0; s < per_series.size(); ++s) {
      EXPECT_GE(per_series[s], 60) << "plot at " << rect.dump() << ": series " << s << " is missing";
    }
  }
  // The first scene's twelve plots fit in 3000 pixels.
  EXPECT_GE(visible, 12);

  const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  std::printf("report browser test: %d plots, %d checked in the screenshot (least coloured pixels in a plot %d, "
              "of one series %d), %.1f s\n", kExpectedPlots, visible, least_coloured, least_series, seconds);
  if (!HasFailure()) std::filesystem::remove_all(dir);
}

// Edge cases: no disoccluded pixels (so no masked plots), no insets, constant errors (a log
// scale over one value), a zero error (linear scale), a NaN (null in the data, left out), a run
// without pass timings, one frame only.
TEST(ReportBrowser, EdgeCasesDrawWithoutConsoleOutput) {
  Report report = testing::synthetic_report({.scenes = 1, .frames = 5, .masked = false, .insets = false});
  for (auto& f : report.runs[0].frames) f.whole = {0.25, 0.25, 0.25};
  report.runs[1].frames[2].whole.relmse = 0.0;
  report.runs[1].frames[3].whole.mape = std::nan("");
  for (auto& f : report.runs[2].frames) f.pass_ms.clear();
  report.runs[2].frames.resize(1);
  Page page;
  nlohmann::json rects;
  ASSERT_NO_FATAL_FAILURE(load_page(report, "edge", 1 * 2 * 3, page, rects));
  if (!HasFailure()) std::filesystem::remove_all(page.dir);
}

}  // namespace
}  // namespace strata::report
