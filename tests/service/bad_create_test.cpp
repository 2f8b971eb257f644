// Bad requests to the unary RPCs: each answered with the right status and a message naming the
// field and the limit, while another session keeps streaming undisturbed.
#include <cmath>
#include <filesystem>
#include <fstream>
#include <limits>

#include "harness.h"
#include "scene/scene_io.h"

namespace strata::test {
namespace {

using grpc::StatusCode;

struct Case {
  std::string what;
  v1::CreateSessionRequest request;
  StatusCode code;
  std::string message;  // a part of the message
};

class BadCreateTest : public ServiceTest {
 protected:
  v1::CreateSessionRequest ok_request() { return session_request("cornell", 32, 24); }
  v1::CreateSessionRequest with_path(const std::string& path) {
    auto r = ok_request();
    r.mutable_scene()->set_path(path);
    return r;
  }
  v1::CreateSessionRequest with_glb(const std::vector<uint8_t>& bytes) {
    auto r = ok_request();
    r.mutable_scene()->set_glb(std::string(bytes.begin(), bytes.end()));
    return r;
  }
  void expect(const grpc::Status& st, StatusCode code, const std::string& message, const std::string& what) {
    EXPECT_EQ(st.error_code(), code) << what << ": " << st.error_message();
    EXPECT_NE(st.error_message().find(message), std::string::npos)
        << what << ": message '" << st.error_message() << "' does not contain '" << message << "'";
  }
};

TEST_F(BadCreateTest, EveryBadRequestGetsItsStatusAndMessage) {
  const v1::Session other = create_ok(stub(), session_request("carousel", 24, 16));
  BackgroundStream background(address(), other.name());
  ASSERT_TRUE(wait_until([&] { return background.frames() >= 2; }, 30s));

  // Files for the path cases: one outside the scene directory, and a link to it from inside.
  TempDir outside;
  const auto cornell = scene::export_glb(scene::builtin_scene("cornell"));
  scene::export_glb_file(scene::builtin_scene("cornell"), outside.path / "outside.glb");
  std::filesystem::create_symlink(outside.path / "outside.glb", scene_dir_.path / "link.glb");
  std::ofstream(scene_dir_.path / "scene.txt") << "text";
  scene::Scene crowd = scene::builtin_scene("cornell");
  while (crowd.instances.size() <= config_.limits.max_instances) crowd.instances.push_back(crowd.instances.front());

  const float nan = std::numeric_limits<float>::quiet_NaN();
  std::vector<Case> cases;
  auto add = [&](std::string what, auto edit, StatusCode code, std::string message) {
    v1::CreateSessionRequest r = ok_request();
    edit(r);
    cases.push_back({std::move(what), std::move(r), code, std::move(message)});
  };
  const auto invalid = StatusCode::INVALID_ARGUMENT;
  add("no scene", [](auto& r) { r.clear_scene(); }, invalid, "scene is required");
  add("unknown built-in", [](auto& r) { r.mutable_scene()->set_builtin("nope"); }, invalid,
      "scene.builtin = 'nope' is not a built-in scene; built-in scenes: cornell");
  cases.push_back({"path escaping with ..", with_path("../../etc/passwd.glb"), StatusCode::PERMISSION_DENIED,
                   "outside the scene directory"});
  cases.push_back({"absolute path outside", with_path((outside.path / "outside.glb").string()), StatusCode::PERMISSION_DENIED,
                   "outside the scene directory"});
  cases.push_back({"link to outside", with_path("link.glb"), StatusCode::PERMISSION_DENIED, "outside the scene directory"});
  cases.push_back({"not a scene file", with_path("scene.txt"), invalid, "scene.path = 'scene.txt' is not a .gltf or .glb file"});
  cases.push_back({"missing file", with_path("missing.glb"), StatusCode::NOT_FOUND, "scene.path = 'missing.glb' does not exist"});
  cases.push_back({"truncated .glb", with_glb({cornell.begin(), cornell.begin() + long(cornell.size() / 2)}), invalid, "scene.glb"});
  cases.push_back({"not a glTF at all", with_glb({'n', 'o', 't', ' ', 'g', 'l', 'b'}), invalid, "scene.glb"});
  cases.push_back({"oversize .glb", with_glb(std::vector<uint8_t>(config_.limits.max_scene_bytes + 1, 0)), invalid,
                   "max_scene_bytes = " + std::to_string(config_.limits.max_scene_bytes)});
  cases.push_back({"too many instances", with_glb(scene::export_glb(crowd)), invalid, "max_instances"});
  add("missing resolution", [](auto& r) { r.clear_resolution(); }, invalid, "resolution is required");
  add("zero width", [](auto& r) { r.mutable_resolution()->set_width(0); }, invalid, "resolution.width = 0 is outside [1, 1024]");
  add("width over max_dimension", [](auto& r) { r.mutable_resolution()->set_width(2000); }, invalid,
      "resolution.width = 2000 is outside [1, 1024] (max_dimension)");
  add("oversize resolution", [](auto& r) { r.mutable_resolution()->set_width(1024); r.mutable_resolution()->set_height(1024); },
      invalid, "exceeds max_pixels = 307200");
  add("unknown method", [](auto& r) { r.set_method("magic"); }, invalid, "method = 'magic' is not a method");
  add("method not implemented", [](auto& r) { r.set_method("restir-lod"); }, invalid,
      "method = 'restir-lod' is not a method; methods: auto, pt, restir-gather, restir-di, restir-splat, restir-splat-backup, restir-multilayer");
  add("spp 0", [](auto& r) { r.mutable_options()->set_spp(0); }, invalid, "options.spp = 0 is outside [1, 64] (limit max_spp)");
  add("spp over max_spp", [](auto& r) { r.mutable_options()->set_spp(65); }, invalid, "options.spp = 65 is outside [1, 64] (limit max_spp)");
  add("max_depth over the limit", [](auto& r) { r.mutable_options()->set_max_depth(33); }, invalid, "options.max_depth = 33");
  add("NaN confidence cap", [&](auto& r) { r.mutable_options()->set_confidence_cap(nan); }, invalid, "options.confidence_cap = nan");
  add("layers out of range", [](auto& r) { r.mutable_options()->set_layers(9); }, invalid, "options.layers = 9 is outside [0, 8]");
  add("unknown shift", [](auto& r) { r.mutable_options()->mutable_experimental()->set_shift(static_cast<v1::Shift>(7)); }, invalid,
      "options.experimental.shift = 7 is not one of");
  add("negative spatial radius", [](auto& r) { r.mutable_options()->set_spatial_radius(-1.0f); }, invalid,
      "options.spatial_radius = -1 is outside [1, 256] pixels");
  add("unknown encoding", [](auto& r) { r.clear_encodings(); r.add_encodings(static_cast<v1::ImageEncoding>(9)); }, invalid,
      "encodings[0] = 9 is not an image encoding");
  add("encoding twice", [](auto& r) { r.add_encodings(v1::IMAGE_ENCODING_RAW_RGBA16F); }, invalid, "requested twice");
  // Environment maps (SceneSource.environment).
  std::ofstream(scene_dir_.path / "sky.png") << "\x89PNG\r\n\x1a\n";
  add("environment without a source", [](auto& r) { r.mutable_scene()->mutable_environment()->set_intensity(2.0f); }, invalid,
      "scene.environment is set without a source");
  add("environment not an HDR image", [](auto& r) { r.mutable_scene()->mutable_environment()->set_image("not an image at all"); },
      invalid, "is not an HDR image (Radiance .hdr or OpenEXR)");
  add("environment path of another kind", [](auto& r) { r.mutable_scene()->mutable_environment()->set_path("sky.png"); }, invalid,
      "scene.environment.path = 'sky.png' is not a .hdr or .exr file");
  add("environment path outside", [](auto& r) { r.mutable_scene()->mutable_environment()->set_path("../sky.hdr"); },
      StatusCode::PERMISSION_DENIED, "outside the scene directory");
  add("missing environment file", [](auto& r) { r.mutable_scene()->mutable_environment()->set_path("missing.hdr"); },
      StatusCode::NOT_FOUND, "scene.environment.path = 'missing.hdr' does not exist");
  add("NaN environment intensity", [&](auto& r) {
    r.mutable_scene()->mutable_environment()->set_image("x");
    r.mutable_scene()->mutable_environment()->set_intensity(nan);
  }, invalid, "scene.environment.intensity = nan is not a finite number >= 0");
  add("infinite environment rotation", [&](auto& r) {
    r.mutable_scene()->mutable_environment()->set_image("x");
    r.mutable_scene()->mutable_environment()->set_rotation_degrees(std::numeric_limits<float>::infinity());
  }, invalid, "scene.environment.rotation_degrees = inf is not finite");
  add("oversize environment", [&](auto& r) {
    r.mutable_scene()->mutable_environment()->set_image(std::string(config_.limits.max_environment_bytes + 1, 'x'));
  }, invalid, "max_environment_bytes = " + std::to_string(config_.limits.max_environment_bytes));
  ASSERT_GE(cases.size(), 20u);

  const uint64_t before = background.frames();
  for (const auto& c : cases) {
    v1::Session s;
    expect(create_session(stub(), c.request, &s), c.code, c.message, c.what);
  }

  // Names and pages.
  v1::Session s;
  expect(get_session(stub(), "foo", &s), StatusCode::INVALID_ARGUMENT, "name = 'foo' is not a session name", "malformed name");
  expect(get_session(stub(), "sessions/UPPER", &s), StatusCode::INVALID_ARGUMENT, "is not a session name", "upper case id");
  expect(get_session(stub(), "sessions/0123456789abcdef", &s), StatusCode::NOT_FOUND, "does not exist", "unknown session");
  expect(delete_session(stub(), "sessions/0123456789abcdef"), StatusCode::NOT_FOUND, "does not exist", "delete unknown");
  {
    grpc::ClientContext ctx;
    v1::ListSessionsRequest req;
    req.set_page_size(-1);
    v1::ListSessionsResponse resp;
    expect(stub().ListSessions(&ctx, req, &resp), StatusCode::INVALID_ARGUMENT, "page_size = -1 must be >= 0", "negative page");
  }
  {
    grpc::ClientContext ctx;
    v1::ListSessionsRequest req;
    req.set_page_token("garbage");
    v1::ListSessionsResponse resp;
    expect(stub().ListSessions(&ctx, req, &resp), StatusCode::INVALID_ARGUMENT, "page_token = 'garbage'", "bad page token");
  }

  // max_sessions: the background session plus three more fill the server.
  std::vector<std::string> extra;
  for (uint32_t i = 1; i < config_.limits.max_sessions; ++i) extra.push_back(create_ok(stub(), ok_request()).name());
  expect(create_session(stub(), ok_request(), &s), StatusCode::RESOURCE_EXHAUSTED, "max_sessions = 4", "max sessions");
  for (const auto& name : extra) EXPECT_TRUE(delete_session(stub(), name).ok());
  EXPECT_TRUE(create_session(stub(), ok_request(), &s).ok()) << "a place is free again";

  // The other session streamed all along.
  ASSERT_TRUE(wait_until([&] { return background.frames() > before + 2; }, 30s));
  const grpc::Status bg = background.stop();
  EXPECT_TRUE(bg.ok()) << bg.error_message();
  EXPECT_EQ(server_status(stub()).sessions(), 2u);
}

}  // namespace
}  // namespace strata::test
