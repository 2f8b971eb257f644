// Unit tests of strata_report: results.csv rows and quoting, results.json structure, report.html's
// data block, escaping and self-containment, and the error-map PNGs.
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <limits>
#include <regex>
#include <sstream>
#include <string>
#include <unistd.h>
#include <vector>

#include "image/image.h"
#include "report/report.h"
#include "synthetic.h"

namespace strata::report {
namespace {

std::vector<std::string> split_lines(const std::string& text) {
  std::vector<std::string> lines;
  std::istringstream in(text);
  for (std::string line; std::getline(in, line);) lines.push_back(line);
  return lines;
}

std::string read_file(const std::filesystem::path& path) {
  std::ifstream in(path, std::ios::binary);
  return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

std::filesystem::path temp_dir(const std::string& name) {
  const auto dir = std::filesystem::temp_directory_path() /
                   ("strata_report_test_" + name + "_" + std::to_string(::getpid()));
  std::filesystem::remove_all(dir);
  std::filesystem::create_directories(dir);
  return dir;
}

// The text between <script type="application/json" id="data"> and its </script>.
std::string data_block(const std::string& html) {
  const std::string open = "<script type=\"application/json\" id=\"data\">";
  const size_t begin = html.find(open);
  if (begin == std::string::npos) return {};
  const size_t start = begin + open.size();
  const size_t end = html.find("</script>", start);
  return html.substr(start, end - start);
}

Run one_frame_run(std::string scene, std::string method, bool masked) {
  FrameResult f;
  f.frame = 3;
  f.gpu_ms = 1.5;
  f.cumulative_ms = 6.0;
  f.pass_ms = {{"trace", 1.0}, {"shade", 0.5}};
  f.whole = {0.1, 0.25, 0.125, 0.05};
  f.has_masked = masked;
  if (masked) {
    f.masked = {0.5, 0.75, 0.0625, 0.375};
    f.masked_pixels = 42;
  }
  return Run{std::move(scene), std::move(method), 2, false, "", {f}};
}

TEST(ReportCsv, HeaderAndOneRowPerRunAndFrame) {
  const Report report = testing::synthetic_report({.scenes = 2, .frames = 8});
  const auto lines = split_lines(to_csv(report));
  ASSERT_EQ(lines.size(), 1u + 2 * 3 * 8);
  EXPECT_EQ(lines[0],
            "scene,method,spp,equal_time_pt,frame,gpu_ms,cumulative_ms,relmse,mape,flip,"
            "masked_pixels,masked_relmse,masked_mape,masked_flip,relmse_luminance,masked_relmse_luminance");
  // Frame 0 has no disoccluded pixels: the five masked cells are empty.
  EXPECT_TRUE(lines[1].starts_with("cornell,restir-gather,1,false,0,"));
  EXPECT_NE(lines[1].find(",,,,"), std::string::npos) << lines[1];
  EXPECT_TRUE(lines[1].ends_with(",")) << lines[1];
  EXPECT_TRUE(lines[2].starts_with("cornell,restir-gather,1,false,1,"));
  EXPECT_NE(lines[2].find(",110,"), std::string::npos) << lines[2];  // masked_pixels of frame 1
  EXPECT_TRUE(lines[17].starts_with("cornell,pt,4,true,0,"));
  EXPECT_TRUE(lines[25].starts_with("chess,restir-gather,1,false,0,"));
  for (const auto& line : lines) EXPECT_EQ(std::count(line.begin(), line.end(), ','), 15) << line;
}

TEST(ReportCsv, ExactValuesMaskedCellsAndSceneGrouping) {
  Report report;
  report.runs.push_back(one_frame_run("a", "pt", true));
  report.runs.push_back(one_frame_run("b", "restir-gather", false));
  report.runs.push_back(one_frame_run("a", "restir-di", false));
  const auto lines = split_lines(to_csv(report));
  ASSERT_EQ(lines.size(), 4u);
  EXPECT_EQ(lines[1], "a,pt,2,false,3,1.5,6,0.1,0.25,0.125,42,0.5,0.75,0.0625,0.05,0.375");
  EXPECT_EQ(lines[2], "a,restir-di,2,false,3,1.5,6,0.1,0.25,0.125,,,,,0.05,");  // grouped by scene
  EXPECT_EQ(lines[3], "b,restir-gather,2,false,3,1.5,6,0.1,0.25,0.125,,,,,0.05,");
}

TEST(ReportCsv, QuotesFieldsThatNeedIt) {
  Report report;
  report.runs.push_back(one_frame_run("my \"big\", scene", "pt", false));
  report.runs.push_back(one_frame_run("line\nbreak", " padded", false));
  const std::string csv = to_csv(report);
  EXPECT_NE(csv.find("\n\"my \"\"big\"\", scene\",pt,2,"), std::string::npos) << csv;
  EXPECT_NE(csv.find("\n\"line\nbreak\",\" padded\",2,"), std::string::npos) << csv;
}

TEST(ReportCsv, WriteCsvWritesTheSameTextAndFailsLoudly) {
  const auto dir = temp_dir("csv");
  const Report report = testing::synthetic_report({.scenes = 1, .frames = 2, .insets = false});
  write_csv(report, dir / "sub" / "results.csv");
  EXPECT_EQ(read_file(dir / "sub" / "results.csv"), to_csv(report));
  EXPECT_THROW(write_csv(report, dir / "sub"), ReportError);  // a directory
  std::filesystem::remove_all(dir);
}

TEST(ReportJson, Structure) {
  const Report report = testing::synthetic_report({.scenes = 2, .frames = 8});
  const nlohmann::json j = to_json(report);
  EXPECT_EQ(j["meta"]["device"], "llvmpipe (synthetic)");
  ASSERT_EQ(j["runs"].size(), 6u);
  const auto& run = j["runs"][2];
  EXPECT_EQ(run["scene"], "cornell");
  EXPECT_EQ(run["method"], "pt");
  EXPECT_EQ(run["spp"], 4);
  EXPECT_EQ(run["equal_time_pt"], true);
  EXPECT_EQ(run["matched_method"], "restir-gather");
  ASSERT_EQ(run["frames"].size(), 8u);
  const auto& f0 = run["frames"][0];
  EXPECT_EQ(f0["frame"], 0);
  EXPECT_EQ(f0["has_masked"], false);
  EXPECT_TRUE(f0["masked"].is_null());
  EXPECT_DOUBLE_EQ(f0["pass_ms"]["trace"].get<double>(), report.runs[2].frames[0].pass_ms.at("trace"));
  EXPECT_DOUBLE_EQ(f0["gpu_ms"].get<double>(), report.runs[2].frames[0].gpu_ms);
  const auto& f1 = run["frames"][1];
  EXPECT_EQ(f1["has_masked"], true);
  EXPECT_EQ(f1["masked_pixels"], 110);
  EXPECT_DOUBLE_EQ(f1["masked"]["relmse"].get<double>(), report.runs[2].frames[1].masked.relmse);
  EXPECT_DOUBLE_EQ(f1["whole"]["flip"].get<double>(), report.runs[2].frames[1].whole.flip);
  EXPECT_DOUBLE_EQ(f1["cumulative_ms"].get<double>(), report.runs[2].frames[1].cumulative_ms);

  ASSERT_EQ(j["equal_time"].size(), 2u);
  const auto& et = j["equal_time"][1];
  EXPECT_EQ(et["scene"], "chess");
  EXPECT_EQ(et["pt_spp"], 4);
  EXPECT_DOUBLE_EQ(et["ratio"]["relmse"].get<double>(), 0.2);
  EXPECT_DOUBLE_EQ(et["pt_mean"]["mape"].get<double>(), 0.01);
  EXPECT_DOUBLE_EQ(et["method_median_ms"].get<double>(), 4.0);

  ASSERT_EQ(j["insets"].size(), 2u);
  EXPECT_EQ(j["insets"][0]["scene"], "cornell");
  EXPECT_EQ(j["insets"][0]["frame"], 7);
  EXPECT_EQ(j["insets"][0]["images"],
            nlohmann::json({"reference", "restir-gather", "pt", "error:restir-gather", "error:pt"}));
}

TEST(ReportJson, WriteJsonRoundTrips) {
  const auto dir = temp_dir("json");
  const Report report = testing::synthetic_report({.scenes = 1, .frames = 3});
  write_json(report, dir / "results.json");
  EXPECT_EQ(nlohmann::json::parse(read_file(dir / "results.json")), to_json(report));
  std::filesystem::remove_all(dir);
}

TEST(ReportJson, EmptyReport) {
  const nlohmann::json j = to_json(Report{});
  EXPECT_TRUE(j["meta"].is_object());
  EXPECT_TRUE(j["runs"].is_array() && j["runs"].empty());
  EXPECT_TRUE(j["equal_time"].is_array());
  EXPECT_TRUE(j["insets"].is_array());
}

TEST(ReportHtml, DataBlockIsEscapedAndParses) {
  Report report = testing::synthetic_report({.scenes = 2, .frames = 8});
  report.runs[0].method = "<!--</script>";
  const std::string html = to_html(report);
  const std::string block = data_block(html);
  ASSERT_FALSE(block.empty());
  EXPECT_EQ(block.find("</"), std::string::npos);
  EXPECT_EQ(block.find("<!--"), std::string::npos);
  EXPECT_NE(block.find("<\\/script>"), std::string::npos);
  const nlohmann::json data = nlohmann::json::parse(block);
  EXPECT_EQ(data["meta"]["command_line"], report.meta["command_line"]);
  EXPECT_EQ(data["runs"][0]["method"], "<!--</script>");
  EXPECT_EQ(data["scenes"], nlohmann::json({"cornell", "chess"}));
  EXPECT_EQ(data["runs"], to_json(report)["runs"]);
  // Outside the data block there are exactly three scripts (the block, uPlot, the page script):
  // the meta's "</script><script>" did not open a new element.
  std::string rest = html;
  rest.erase(rest.find(block), block.size());
  size_t scripts = 0;
  for (size_t pos = rest.find("<script"); pos != std::string::npos; pos = rest.find("<script", pos + 1)) ++scripts;
  EXPECT_EQ(scripts, 3u);
}

TEST(ReportHtml, SelfContained) {
  const Report report = testing::synthetic_report({.scenes = 2, .frames = 8});
  const std::string html = to_html(report);
  // Nothing is loaded from elsewhere: no element with a src/href to http(s) or protocol-relative
  // URLs, no external stylesheet or script at all.
  const std::regex remote(R"re(<(script|link|img|iframe|source|embed|object)\b[^>]*\b(src|href|data)\s*=\s*["']?\s*(https?:)?//)re",
                          std::regex::icase);
  EXPECT_FALSE(std::regex_search(html, remote));
  EXPECT_EQ(html.find("<link"), std::string::npos);
  EXPECT_EQ(html.find("<script src"), std::string::npos);
  EXPECT_EQ(html.find("@import"), std::string::npos);
  // uPlot and the page script are inlined.
  EXPECT_EQ(uplot_version(), "1.6.32");
  EXPECT_NE(html.find("var uPlot=function()"), std::string::npos);
  EXPECT_NE(html.find("document.body.dataset.plots"), std::string::npos);
  EXPECT_NE(html.find(".uplot"), std::string::npos);  // uPlot's stylesheet
  // Every inset image is a data: URI of its PNG bytes.
  size_t images = 0;
  for (size_t pos = html.find("src=\"data:image/png;base64,"); pos != std::string::npos;
       pos = html.find("src=\"data:image/png;base64,", pos + 1)) {
    ++images;
  }
  EXPECT_EQ(images, 10u);
}

TEST(ReportHtml, EscapesTextAndHighlightsRatios) {
  Report report;
  report.runs.push_back(one_frame_run("<b>scene</b>", "pt", false));
  report.equal_time.push_back(EqualTime{"<b>scene</b>", "restir-gather", 3.0, 3.1, 2, {}, {}, {0.5, 1.5, 1.0}});
  report.insets.push_back(Insets{"<b>scene</b>", 0, {{"ref", std::vector<uint8_t>{1, 2, 3, 4}}}});
  const std::string html = to_html(report);
  EXPECT_EQ(html.find("<b>scene</b>"), std::string::npos);
  EXPECT_NE(html.find("&lt;b&gt;scene&lt;/b&gt;"), std::string::npos);
  EXPECT_NE(html.find("<td class=\"num good\">0.5</td>"), std::string::npos);
  EXPECT_NE(html.find("<td class=\"num bad\">1.5</td>"), std::string::npos);
  EXPECT_NE(html.find("<td class=\"num\">1</td>"), std::string::npos);
  EXPECT_NE(html.find("src=\"data:image/png;base64,AQIDBA==\""), std::string::npos);  // base64 of 1 2 3 4
}

TEST(ReportHtml, WriteHtml) {
  const auto dir = temp_dir("html");
  const Report report = testing::synthetic_report({.scenes = 1, .frames = 2});
  write_html(report, dir / "report.html");
  EXPECT_EQ(read_file(dir / "report.html"), to_html(report));
  std::filesystem::remove_all(dir);
}

// Decoded pixel (x, y) as 8-bit RGB.
std::array<int, 3> rgb_at(const image::Image& img, uint32_t x, uint32_t y) {
  const float* p = img.pixel(x, y);
  return {int(std::lround(p[0] * 255.0f)), int(std::lround(p[1] * 255.0f)), int(std::lround(p[2] * 255.0f))};
}

TEST(ReportErrorMap, DecodesToTheRightSizeAndColourMapEndpoints) {
  const uint32_t width = 5, height = 3;
  const float nan = std::numeric_limits<float>::quiet_NaN();
  const float inf = std::numeric_limits<float>::infinity();
  // Row 0: 0, max/2, max, 2*max (clamped), -1 (clamped); row 1: NaN, inf, then a ramp.
  std::vector<float> values = {0.0f, 1.0f, 2.0f, 4.0f, -1.0f, nan, inf, 0.5f, 1.5f, 0.25f,
                               0.0f, 0.0f, 0.0f, 0.0f, 2.0f};
  const auto png = error_map_png(values, width, height, 2.0f);
  ASSERT_GT(png.size(), 8u);
  EXPECT_EQ(png[1], 'P');
  const image::Image img = image::decode_png(png);
  ASSERT_EQ(img.width, width);
  ASSERT_EQ(img.height, height);
  const std::array<int, 3> low = {0, 0, 4}, high = {252, 253, 191}, mid = {183, 55, 121};
  EXPECT_EQ(rgb_at(img, 0, 0), low);
  EXPECT_EQ(rgb_at(img, 1, 0), mid);  // magma(0.5)
  EXPECT_EQ(rgb_at(img, 2, 0), high);
  EXPECT_EQ(rgb_at(img, 3, 0), high);
  EXPECT_EQ(rgb_at(img, 4, 0), low);
  EXPECT_EQ(rgb_at(img, 0, 1), high);
  EXPECT_EQ(rgb_at(img, 1, 1), high);
  EXPECT_EQ(rgb_at(img, 4, 2), high);
  // Monotone in brightness along the ramp 0.25, 0.5, 1, 1.5 (of 2).
  const auto luma = [&](uint32_t x, uint32_t y) {
    const auto c = rgb_at(img, x, y);
    return 0.2126 * c[0] + 0.7152 * c[1] + 0.0722 * c[2];
  };
  EXPECT_LT(luma(4, 1), luma(2, 1));
  EXPECT_LT(luma(2, 1), luma(1, 0));
  EXPECT_LT(luma(1, 0), luma(3, 1));
  EXPECT_LT(luma(3, 1), luma(2, 0));
}

TEST(ReportErrorMap, RejectsBadArguments) {
  EXPECT_THROW(error_map_png({1.0f, 2.0f}, 3, 1), ReportError);
  EXPECT_THROW(error_map_png({}, 0, 0), ReportError);
  EXPECT_THROW(error_map_png({1.0f}, 1, 1, 0.0f), ReportError);
  EXPECT_THROW(error_map_png({1.0f}, 1, 1, std::numeric_limits<float>::quiet_NaN()), ReportError);
}

}  // namespace
}  // namespace strata::report
