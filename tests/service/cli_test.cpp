// The command-line client against a stratad process: `strata stream` reproduces `stratad render`
// byte for byte for the same seed (the domain map too), follows a camera/transform/LoD script, and
// reports errors.
#include <cmath>
#include <cstdio>
#include <fstream>

#include <nlohmann/json.hpp>

#include "process.h"

namespace strata::test {
namespace {

namespace fs = std::filesystem;

std::string read_file(const fs::path& p) {
  std::ifstream in(p, std::ios::binary);
  return std::string(std::istreambuf_iterator<char>(in), {});
}

std::vector<std::string> stream_args(const std::string& address, const fs::path& out) {
  return {strata_path(), "stream", "--server", address, "--scene", "cornell", "--method", "pt", "--width", "32",
          "--height", "24", "--spp", "2", "--frames", "3", "--seed", "5", "--out", out.string()};
}

TEST(CliTest, StrataStreamReproducesStratadRenderForTheSameSeed) {
  TempDir dir;
  Daemon daemon;
  const auto render = run_process({stratad_path(), "render", "--scene", "cornell", "--method", "pt", "--width", "32", "--height",
                                   "24", "--spp", "2", "--frames", "3", "--seed", "5", "--out", (dir.path / "render").string()},
                                  120s);
  ASSERT_EQ(render.exit_code, 0) << render.output;
  const auto stream = run_process(stream_args(daemon.address(), dir.path / "stream"), 120s);
  ASSERT_EQ(stream.exit_code, 0) << stream.output;
  auto raw_args = stream_args(daemon.address(), dir.path / "raw");
  raw_args.insert(raw_args.end(), {"--encodings", "raw"});
  const auto raw = run_process(raw_args, 120s);
  ASSERT_EQ(raw.exit_code, 0) << raw.output;

  for (const char* stem : {"frame_0000", "frame_0001", "frame_0002"}) {
    SCOPED_TRACE(stem);
    const std::string exr = read_file(dir.path / "render" / (std::string(stem) + ".exr"));
    ASSERT_FALSE(exr.empty());
    EXPECT_TRUE(read_file(dir.path / "stream" / (std::string(stem) + ".exr")) == exr) << "EXR differs from stratad render's";
    EXPECT_TRUE(read_file(dir.path / "stream" / (std::string(stem) + ".png")) ==
                read_file(dir.path / "render" / (std::string(stem) + ".png")))
        << "PNG differs from stratad render's";
    EXPECT_TRUE(read_file(dir.path / "raw" / (std::string(stem) + ".exr")) == exr) << "EXR made from RAW_RGBA16F differs";
  }
  EXPECT_FALSE(read_file(dir.path / "stream" / "frame_0000.exr") == read_file(dir.path / "stream" / "frame_0001.exr"));

  const auto doc = nlohmann::json::parse(read_file(dir.path / "stream" / "frames.json"));
  ASSERT_EQ(doc["frames"].size(), 3u);
  for (const auto& f : doc["frames"]) {
    EXPECT_GT(std::stoull(f["statistics"]["rays_total"].get<std::string>()), 0u);
    EXPECT_FALSE(f["pass_ms"].empty());
    EXPECT_TRUE(f.contains("gpu_ms_total"));
    EXPECT_TRUE(f["client"].contains("latency_ms"));
    EXPECT_EQ(f["files"]["exr"].get<std::string>().substr(0, 6), "frame_");
  }
  EXPECT_EQ(doc["summary"]["frames_received"], 3);
  EXPECT_EQ(doc["session"]["scene"], "cornell");
  EXPECT_TRUE(doc["session"].contains("decisions"));

  // The sessions were deleted at the end.
  auto stub = v1::RenderService::NewStub(loopback_channel(daemon.address()));
  grpc::ClientContext ctx;
  v1::ListSessionsResponse sessions;
  ASSERT_TRUE(stub->ListSessions(&ctx, {}, &sessions).ok());
  EXPECT_EQ(sessions.sessions_size(), 0);
}

TEST(CliTest, CameraPathScriptDrivesCameraLodAndResolution) {
  TempDir dir;
  Daemon daemon;
  const fs::path script = dir.path / "path.json";
  std::ofstream(script) << R"({"frames": [
    {"animation_frame": 0},
    {"camera": {"position": {"x": 0.1, "y": 1.0, "z": 3.5}, "orientation": {"w": 1}, "vertical_fov": 0.7},
     "transforms": [{"instance_id": 1, "translation": {"x": 0.05}, "rotation": {"w": 1}, "scale": {"x": 1, "y": 1, "z": 1}}]},
    {"resolution": {"width": 40, "height": 30}, "options": {"spp": 3}, "lod_changes": [{"instance_id": 0, "level": 0}]}
  ]})";
  const auto r = run_process({strata_path(), "stream", "--server", daemon.address(), "--scene", "cornell", "--method", "pt", "--width", "32",
                              "--height", "24", "--camera-path", script.string(), "--out", (dir.path / "out").string()},
                             120s);
  ASSERT_EQ(r.exit_code, 0) << r.output;
  const auto doc = nlohmann::json::parse(read_file(dir.path / "out" / "frames.json"));
  ASSERT_EQ(doc["frames"].size(), 3u);
  const auto& last = doc["frames"][2];
  EXPECT_TRUE(last["history_reset"].get<bool>());
  EXPECT_NE(last["history_reset_reason"].get<std::string>().find("resolution changed from 32x24 to 40x30"), std::string::npos);
  EXPECT_EQ(last["resolution"]["width"], 40);
  const auto bytes = read_file(dir.path / "out" / "frame_0002.exr");
  const image::Image img = image::decode_exr(std::vector<uint8_t>(bytes.begin(), bytes.end()));
  EXPECT_EQ(img.width, 40u);
  EXPECT_EQ(img.height, 30u);
  EXPECT_EQ(std::stoull(last["statistics"]["paths"].get<std::string>()), 40u * 30u * 3u);
}

// A script that poses the characters scene's skinned flag (FrameInput.joint_poses): flat twice, then
// folded back towards the wall, which narrows the flag's silhouette. Under the warm ceiling light
// (radiance 17, 12, 4) every other surface reflects far more red than blue (blue under a quarter of
// red for white), the blue cloth about as much of each: the share of pixels whose blue exceeds 0.6x
// their red measures the flag.
TEST(CliTest, CameraPathScriptPosesASkinnedInstance) {
  TempDir dir;
  Daemon daemon;
  // The flag's 5 joints from the pole (x = -0.55, z = -0.25) 0.25 m apart, each turned `a` about +Y
  // from the one before: joint to world of each.
  auto pose = [](double a) {
    std::string joints;
    double heading = 0.0, x = -0.55, z = -0.25;
    for (int k = 0; k < 5; ++k) {
      if (k > 0) {
        x += 0.25 * std::cos(heading);
        z -= 0.25 * std::sin(heading);
        heading += a;
      }
      joints += (k ? "," : "") + std::string("{\"joint\": ") + std::to_string(k) + ", \"translation\": {\"x\": " + std::to_string(x) +
                ", \"y\": 1.35, \"z\": " + std::to_string(z) + "}, \"rotation\": {\"w\": " + std::to_string(std::cos(0.5 * heading)) +
                ", \"y\": " + std::to_string(std::sin(0.5 * heading)) + "}}";
    }
    return "\"joint_poses\": [{\"instance_id\": 3, \"joints\": [" + joints + "]}]";
  };
  const fs::path script = dir.path / "pose.json";
  std::ofstream(script) << "{\"frames\": [{\"animation_frame\": 0, " << pose(0.0) << "}, {" << pose(0.0) << "}, {" << pose(0.6)
                        << "}]}";
  const auto r = run_process({strata_path(), "stream", "--server", daemon.address(), "--scene", "characters", "--method", "pt",
                              "--width", "48", "--height", "48", "--spp", "16", "--camera-path", script.string(), "--out",
                              (dir.path / "out").string()},
                             120s);
  ASSERT_EQ(r.exit_code, 0) << r.output;
  double flag[3];
  for (int f = 0; f < 3; ++f) {
    const auto bytes = read_file(dir.path / "out" / ("frame_000" + std::to_string(f) + ".exr"));
    const image::Image img = image::decode_exr(std::vector<uint8_t>(bytes.begin(), bytes.end()));
    size_t n = 0;
    for (size_t i = 0; i < img.rgba.size(); i += 4) {
      if (img.rgba[i] > 0.0f && img.rgba[i + 2] > 0.6f * img.rgba[i]) ++n;
    }
    flag[f] = double(n) / double(img.width * img.height);
  }
  std::printf("flag share of the image: flat %.4f, flat again %.4f, folded %.4f\n", flag[0], flag[1], flag[2]);
  // The same pose twice: the same silhouette but for noise at its edge; folded: a narrower one.
  EXPECT_GT(flag[0], 0.05) << "the flat flag is not in view";
  EXPECT_NEAR(flag[1], flag[0], 0.01);
  EXPECT_LT(flag[2], flag[1] - 0.02) << "folding the flag did not narrow its silhouette: " << flag[1] << " -> " << flag[2];
}

TEST(CliTest, StrataStreamSendsRestirOptionsAndLogsReuse) {
  TempDir dir;
  Daemon daemon;
  const auto r = run_process({strata_path(), "stream", "--server", daemon.address(), "--scene", "cornell", "--method",
                              "restir-gather", "--width", "16", "--height", "16", "--frames", "2", "--encodings", "raw",
                              "--shift", "reconnection", "--mis", "balance", "--confidence-cap", "10", "--still-confidence-cap", "12", "--spatial-neighbors",
                              "2", "--spatial-radius", "12", "--initial-candidates", "2", "--light-candidates", "3",
                              "--disocclusion-spatial-neighbors", "5", "--direct-strata", "2", "--no-temporal-filter",
                              "--biased", "--out", (dir.path / "out").string()},
                             120s);
  ASSERT_EQ(r.exit_code, 0) << r.output;
  EXPECT_NE(r.output.find("  reuse "), std::string::npos) << "no reuse in the log:\n" << r.output;
  EXPECT_NE(r.output.find(" temporal.shifts="), std::string::npos) << r.output;
  const auto doc = nlohmann::json::parse(read_file(dir.path / "out" / "frames.json"));
  const auto& o = doc["session"]["options"];
  EXPECT_EQ(doc["session"]["method"], "restir-gather");
  const auto& x = o["experimental"];  // the ablations (RenderOptions.experimental)
  EXPECT_EQ(x["shift"], "SHIFT_RECONNECTION");
  EXPECT_EQ(x["mis"], "MIS_BALANCE");
  EXPECT_EQ(o["confidence_cap"], 10.0);
  EXPECT_EQ(o["still_confidence_cap"], 12.0);
  EXPECT_EQ(o["spatial_neighbors"], 2);
  EXPECT_EQ(o["spatial_radius"], 12.0);
  EXPECT_EQ(o["initial_candidates"], 2);
  EXPECT_EQ(o["light_candidates"], 3);
  EXPECT_EQ(x["unbiased"], false);
  EXPECT_EQ(o["disocclusion_spatial_neighbors"], 5);
  EXPECT_EQ(o["direct_strata"], 2);
  EXPECT_EQ(x["temporal_filter"], false);
  EXPECT_EQ(o["temporal_reuse"], true);
  EXPECT_EQ(o["spatial_reuse"], true);
  ASSERT_EQ(doc["frames"].size(), 2u);
  const auto& reuse = doc["frames"][1]["statistics"]["reuse"];
  ASSERT_TRUE(reuse.contains("counters")) << doc["frames"][1].dump();
  EXPECT_GT(std::stoull(reuse["counters"]["temporal.shifts"].get<std::string>()), 0u);
  EXPECT_TRUE(doc["summary"].contains("reuse"));

  // Without spatial and temporal reuse, and a pt stream has no reuse anywhere.
  const auto off = run_process({strata_path(), "stream", "--server", daemon.address(), "--scene", "cornell", "--method",
                                "restir-gather", "--width", "16", "--height", "16", "--frames", "1", "--encodings", "raw",
                                "--no-temporal", "--no-spatial", "--out", (dir.path / "off").string()},
                               120s);
  ASSERT_EQ(off.exit_code, 0) << off.output;
  const auto off_doc = nlohmann::json::parse(read_file(dir.path / "off" / "frames.json"));
  EXPECT_EQ(off_doc["session"]["options"]["temporal_reuse"], false);
  EXPECT_EQ(off_doc["session"]["options"]["spatial_reuse"], false);
  const auto pt = run_process({strata_path(), "stream", "--server", daemon.address(), "--scene", "cornell", "--method", "pt", "--width", "16",
                               "--height", "16", "--frames", "1", "--encodings", "raw", "--out", (dir.path / "pt").string()},
                              120s);
  ASSERT_EQ(pt.exit_code, 0) << pt.output;
  EXPECT_EQ(pt.output.find("temporal.shifts"), std::string::npos) << pt.output;
  const auto pt_doc = nlohmann::json::parse(read_file(dir.path / "pt" / "frames.json"));
  EXPECT_FALSE(pt_doc["frames"][0]["statistics"].contains("reuse"));
  EXPECT_FALSE(pt_doc["summary"].contains("reuse"));

  // The server's refusal of spp != 1 reaches the user.
  const auto spp = run_process({strata_path(), "stream", "--server", daemon.address(), "--scene", "cornell", "--method",
                                "restir-gather", "--spp", "4", "--width", "16", "--height", "16", "--frames", "1", "--out",
                                (dir.path / "spp").string()},
                               k_render_deadline);
  EXPECT_NE(spp.exit_code, 0);
  EXPECT_NE(spp.output.find("CreateSession: INVALID_ARGUMENT: options.spp = 4"), std::string::npos) << spp.output;
}

// `stratad render --domain-map` writes restir-multilayer's domain map per frame, byte for byte as
// `strata stream --encodings domain` receives it, and refuses a method without pixel layers.
TEST(CliTest, StratadRenderWritesTheDomainMapAsStreamReceivesIt) {
  TempDir dir;
  Daemon daemon;
  const std::vector<std::string> common = {"--scene", "carousel", "--method", "restir-multilayer", "--width", "16", "--height", "16",
                                           "--frames", "3", "--seed", "5", "--max-depth", "3"};
  std::vector<std::string> render = {stratad_path(), "render", "--domain-map", "--out", (dir.path / "render").string()};
  render.insert(render.end(), common.begin(), common.end());
  const auto r = run_process(render, k_render_deadline);
  ASSERT_EQ(r.exit_code, 0) << r.output;
  std::vector<std::string> stream = {strata_path(), "stream", "--server", daemon.address(), "--encodings", "exr,png,domain",
                                     "--out", (dir.path / "stream").string()};
  stream.insert(stream.end(), common.begin(), common.end());
  const auto s = run_process(stream, k_render_deadline);
  ASSERT_EQ(s.exit_code, 0) << s.output;
  for (const char* stem : {"frame_0000", "frame_0001", "frame_0002"}) {
    SCOPED_TRACE(stem);
    const std::string map = read_file(dir.path / "render" / (std::string(stem) + "_domains.png"));
    ASSERT_FALSE(map.empty());
    EXPECT_TRUE(read_file(dir.path / "stream" / (std::string(stem) + "_domains.png")) == map) << "domain map differs from the stream's";
  }
  const auto doc = nlohmann::json::parse(read_file(dir.path / "render" / "frames.json"));
  EXPECT_EQ(doc["frames"][2]["files"]["domain_map"], "frame_0002_domains.png");

  const auto pt = run_process({stratad_path(), "render", "--scene", "cornell", "--method", "pt", "--width", "16", "--height", "16",
                               "--domain-map", "--out", (dir.path / "pt").string()},
                              k_render_deadline);
  EXPECT_NE(pt.exit_code, 0);
  EXPECT_NE(pt.output.find("--domain-map: method pt keeps no pixel layers"), std::string::npos) << pt.output;
}

TEST(CliTest, StrataStreamReportsTheServersError) {
  TempDir dir;
  Daemon daemon;
  auto args = stream_args(daemon.address(), dir.path / "out");
  args[5] = "no-such-scene";
  const auto r = run_process(args, k_render_deadline);
  EXPECT_NE(r.exit_code, 0);
  EXPECT_NE(r.output.find("CreateSession: INVALID_ARGUMENT: scene.builtin = 'no-such-scene' is not a built-in scene"),
            std::string::npos)
      << r.output;

  const fs::path bad = dir.path / "bad.json";
  std::ofstream(bad) << R"({"frames": [{"camera": {"position": {"x": "far"}}}]})";
  auto scripted = stream_args(daemon.address(), dir.path / "out2");
  scripted.insert(scripted.end(), {"--camera-path", bad.string()});
  const auto s = run_process(scripted, k_render_deadline);
  EXPECT_NE(s.exit_code, 0);
  EXPECT_NE(s.output.find("frames[0]"), std::string::npos) << s.output;
}

}  // namespace
}  // namespace strata::test
