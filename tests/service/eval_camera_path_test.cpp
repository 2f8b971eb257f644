// `strata eval --camera-path` end to end: a real `stratad serve` and the real client play a tiny
// camera path with an open shutter (motion blur) and K = 2 splats per frame, and write the
// results with these settings recorded; entries without animation_frame, --shutter without a
// camera path (or with an entry that has no camera) and --frames with a camera path are refused
// before any work.
#include <algorithm>
#include <fstream>

#include <nlohmann/json.hpp>

#include "process.h"

namespace strata::test {
namespace {

namespace fs = std::filesystem;

// Carousel frames 0..n-1 with a camera panning 0.1 m per frame, looking down -Z.
nlohmann::json carousel_path(uint32_t n, bool with_cameras = true) {
  nlohmann::json frames = nlohmann::json::array();
  for (uint32_t i = 0; i < n; ++i) {
    nlohmann::json entry = {{"animation_frame", i}};
    if (with_cameras)
      entry["camera"] = {{"position", {{"x", -1.5 + 0.1 * i}, {"y", 1.6}, {"z", 6.0}}},
                         {"orientation", {{"w", 1.0}}},
                         {"vertical_fov", 0.8}};
    frames.push_back(std::move(entry));
  }
  return {{"frames", frames}};
}

fs::path write_path(const fs::path& dir, const std::string& name, const nlohmann::json& doc) {
  const fs::path p = dir / name;
  std::ofstream(p) << doc.dump(2);
  return p;
}

std::vector<std::string> eval_args(const std::string& address, const fs::path& path, const fs::path& out) {
  return {strata_path(), "eval",  "--server", address,   "--scenes", "carousel", "--methods", "pt,restir-splat",
          "--camera-path", path.string(), "--width", "16", "--height", "16", "--reference-spp", "16",
          "--seed", "2", "--out", out.string()};
}

std::vector<std::string> with(std::vector<std::string> args, const std::vector<std::string>& more) {
  args.insert(args.end(), more.begin(), more.end());
  return args;
}

TEST(EvalCameraPathTest, PlaysACameraPathWithAnOpenShutterAndRecordsTheSettings) {
  TempDir dir;
  Daemon daemon({"--reference-cache", (dir.path / "cache").string()});
  const fs::path path = write_path(dir.path, "path.json", carousel_path(3));
  const fs::path out = dir.path / "out";
  const auto r = run_process(with(eval_args(daemon.address(), path, out), {"--shutter", "0.5", "--splats-per-frame", "2"}), 300s);
  ASSERT_EQ(r.exit_code, 0) << r.output;

  std::ifstream csv(out / "results.csv");
  const std::string text((std::istreambuf_iterator<char>(csv)), {});
  EXPECT_EQ(std::count(text.begin(), text.end(), '\n'), 1 + 2 * 3) << text;  // header, 2 methods x 3 frames
  const auto doc = nlohmann::json::parse(std::ifstream(out / "results.json"));
  ASSERT_EQ(doc["runs"].size(), 2u);
  for (const auto& run : doc["runs"]) {
    ASSERT_EQ(run["frames"].size(), 3u) << run["method"];
    for (const auto& f : run["frames"]) EXPECT_GT(f["whole"]["relmse"].get<double>(), 0.0) << run["method"];
  }
  const auto& meta = doc["meta"];
  EXPECT_EQ(meta["frames"], 3);
  EXPECT_EQ(meta["camera_path"], path.string());
  EXPECT_EQ(meta["shutter"], 0.5);
  EXPECT_EQ(meta["splats_per_frame"], 2);
  const std::string cmd = meta["command_line"];
  for (const std::string& part : {"--camera-path " + path.string(), std::string("--shutter 0.5"), std::string("--splats-per-frame 2")})
    EXPECT_NE(cmd.find(part), std::string::npos) << cmd;
  EXPECT_EQ(cmd.find("--frames"), std::string::npos) << cmd;
  ASSERT_EQ(meta["references"].size(), 3u);
  EXPECT_FALSE(meta["references"][0]["disoccluded_mask"].get<bool>()) << "frame 0 has no previous frame";
  EXPECT_TRUE(meta["references"][2]["disoccluded_mask"].get<bool>()) << "frame 2 has frame 1 before it";
}

TEST(EvalCameraPathTest, BadCameraPathsAndShuttersAreRefusedBeforeAnyWork) {
  TempDir dir;
  const std::string nowhere = "127.0.0.1:1";  // never reached: the checks come first
  const fs::path out = dir.path / "out";
  auto refused = [&](const std::vector<std::string>& args, const std::string& message) {
    const auto r = run_process(args, k_render_deadline);
    EXPECT_NE(r.exit_code, 0) << message;
    EXPECT_NE(r.output.find(message), std::string::npos) << r.output;
  };

  nlohmann::json missing = carousel_path(3);
  missing["frames"][1].erase("animation_frame");
  const fs::path bad = write_path(dir.path, "missing.json", missing);
  refused(eval_args(nowhere, bad, out), bad.string() + ": frames[1] has no animation_frame");

  nlohmann::json options = carousel_path(2);
  options["frames"][0]["options"] = {{"spp", 4}};
  const fs::path opt = write_path(dir.path, "options.json", options);
  refused(eval_args(nowhere, opt, out), opt.string() + ": frames[0] sets options");

  auto no_path = eval_args(nowhere, "", out);
  no_path.erase(no_path.begin() + 8, no_path.begin() + 10);  // --camera-path FILE
  refused(with(no_path, {"--shutter", "0.5"}), "--shutter = 0.5 needs --camera-path whose entries all set camera");
  refused(with(no_path, {"--shutter", "1.5"}), "--shutter = 1.5 is outside [0, 1]");

  nlohmann::json half = carousel_path(3);
  half["frames"][2].erase("camera");
  const fs::path cameraless = write_path(dir.path, "cameraless.json", half);
  refused(with(eval_args(nowhere, cameraless, out), {"--shutter", "0.25"}),
          "--shutter = 0.25 needs a camera in every entry of --camera-path: " + cameraless.string() + ": frames[2] has none");

  const fs::path good = write_path(dir.path, "good.json", carousel_path(2));
  refused(with(eval_args(nowhere, good, out), {"--frames", "2"}), "--frames cannot be given with --camera-path");
  EXPECT_FALSE(fs::exists(out)) << "nothing was started";
}

}  // namespace
}  // namespace strata::test
