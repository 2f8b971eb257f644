// Session lifecycle over real gRPC: create (with the scene analysis, decisions and memory), get,
// list with pages, delete; scenes; server status; memory before and after the first frame.
#include <algorithm>
#include <fstream>

#include "harness.h"
#include "scene/scene_io.h"

namespace strata::test {
namespace {

using LifecycleTest = ServiceTest;

TEST_F(LifecycleTest, CreateReportsAnalysisDecisionsAndMemory) {
  auto req = session_request("cornell", 32, 24, 2, 7);
  req.mutable_options()->set_layers(3);
  const v1::Session s = create_ok(stub(), req);
  EXPECT_EQ(s.name().rfind("sessions/", 0), 0u) << s.name();
  EXPECT_EQ(s.scene(), "cornell");
  EXPECT_EQ(s.method(), "pt");
  EXPECT_EQ(s.seed(), 7u);
  EXPECT_EQ(s.state(), v1::Session::IDLE);
  EXPECT_EQ(s.options().spp(), 2u);
  EXPECT_EQ(s.options().max_depth(), 16u);     // default
  EXPECT_FLOAT_EQ(s.options().confidence_cap(), 4.0f);  // docs/ARCHITECTURE.md, Methods default
  EXPECT_FLOAT_EQ(s.options().spatial_radius(), 4.0f);  // 2.5% of the 24 px height, at least 4 px

  const scene::Scene cornell = scene::builtin_scene("cornell");
  ASSERT_EQ(size_t(s.analysis().instances_size()), cornell.instances.size());
  EXPECT_EQ(s.analysis().triangles(), cornell.triangle_count());
  EXPECT_GT(s.analysis().emissive_triangles(), 0u);
  EXPECT_EQ(s.analysis().instances(0).id(), 0u);

  const v1::Decision* layers = decision(s, "layers");
  ASSERT_NE(layers, nullptr);
  EXPECT_EQ(layers->requested(), "3");
  EXPECT_FALSE(layers->applies());
  EXPECT_NE(layers->reason().find("pt"), std::string::npos) << layers->reason();
  const v1::Decision* lod = decision(s, "lod_mapping");
  ASSERT_NE(lod, nullptr);
  EXPECT_FALSE(lod->applies());
  const v1::Decision* nee = decision(s, "next_event_estimation");
  ASSERT_NE(nee, nullptr);
  EXPECT_TRUE(nee->applies());
  EXPECT_NE(nee->reason().find("emissive triangles"), std::string::npos);

  EXPECT_GT(s.memory().total_bytes(), 0u);
  EXPECT_EQ(s.memory().bytes_by_group().at("image"), 32u * 24u * 16u);
  EXPECT_TRUE(s.has_expire_time());
  EXPECT_GE(s.max_frame_bytes(), 32u * 24u * 8u);
}

TEST_F(LifecycleTest, MemoryAtCreationMatchesTheFirstFramesReport) {
  const v1::Session s = create_ok(stub(), session_request("carousel", 40, 30));
  auto frames = stream_frames(stub(), s.name(), 1);
  ASSERT_EQ(frames.size(), 1u);
  const auto& reported = frames[0].statistics().memory_bytes();
  ASSERT_EQ(size_t(reported.size()), size_t(s.memory().bytes_by_group().size()));
  for (const auto& [group, bytes] : s.memory().bytes_by_group()) {
    ASSERT_TRUE(reported.contains(group)) << group;
    EXPECT_EQ(reported.at(group), bytes) << group;
  }
}

TEST_F(LifecycleTest, GetListPageAndDelete) {
  std::vector<std::string> names;
  for (int i = 0; i < 3; ++i) names.push_back(create_ok(stub(), session_request("cornell", 16, 16)).name());
  std::sort(names.begin(), names.end());

  v1::Session got;
  ASSERT_TRUE(get_session(stub(), names[1], &got).ok());
  EXPECT_EQ(got.name(), names[1]);

  std::vector<std::string> listed;
  std::string token;
  for (int page = 0; page < 5; ++page) {
    grpc::ClientContext ctx;
    v1::ListSessionsRequest req;
    req.set_page_size(1);
    req.set_page_token(token);
    v1::ListSessionsResponse resp;
    ASSERT_TRUE(stub().ListSessions(&ctx, req, &resp).ok());
    ASSERT_LE(resp.sessions_size(), 1);
    for (const auto& s : resp.sessions()) listed.push_back(s.name());
    token = resp.next_page_token();
    if (token.empty()) break;
  }
  EXPECT_EQ(listed, names);

  ASSERT_TRUE(delete_session(stub(), names[0]).ok());
  grpc::Status st = get_session(stub(), names[0], &got);
  EXPECT_EQ(st.error_code(), grpc::StatusCode::NOT_FOUND);
  EXPECT_NE(st.error_message().find("was deleted"), std::string::npos) << st.error_message();
  st = delete_session(stub(), names[0]);
  EXPECT_EQ(st.error_code(), grpc::StatusCode::NOT_FOUND);
  EXPECT_EQ(server_status(stub()).sessions(), 2u);
}

TEST_F(LifecycleTest, ListScenesHasBuiltinsAndSceneDirectoryFiles) {
  scene::export_glb_file(scene::builtin_scene("cornell"), scene_dir_.path / "box.glb");
  std::filesystem::create_directories(scene_dir_.path / "sub");
  scene::export_glb_file(scene::builtin_scene("stiff"), scene_dir_.path / "sub" / "stiff.glb");
  std::ofstream(scene_dir_.path / "notes.txt") << "not a scene";
  grpc::ClientContext ctx;
  v1::ListScenesResponse resp;
  ASSERT_TRUE(stub().ListScenes(&ctx, {}, &resp).ok());
  std::vector<std::string> builtin, files;
  for (const auto& e : resp.scenes()) (e.kind() == v1::SceneEntry::BUILTIN ? builtin : files).push_back(e.name());
  EXPECT_EQ(builtin, scene::builtin_scene_names());
  EXPECT_EQ(files, (std::vector<std::string>{"box.glb", "sub/stiff.glb"}));

  // And a file from the directory makes a session.
  v1::CreateSessionRequest req = session_request("", 16, 16);
  req.mutable_scene()->set_path("sub/stiff.glb");
  const v1::Session s = create_ok(stub(), req);
  EXPECT_EQ(s.analysis().instances_size(), int(scene::builtin_scene("stiff").instances.size()));
}

TEST_F(LifecycleTest, InlineGlbMakesASession) {
  const auto bytes = scene::export_glb(scene::builtin_scene("cornell"));
  v1::CreateSessionRequest req = session_request("", 16, 12);
  req.mutable_scene()->set_glb(std::string(bytes.begin(), bytes.end()));
  req.mutable_scene()->set_label("mine.glb");
  const v1::Session s = create_ok(stub(), req);
  EXPECT_EQ(s.analysis().instances_size(), 4);
  auto frames = stream_frames(stub(), s.name(), 1);
  ASSERT_EQ(frames.size(), 1u);
  EXPECT_GT(frames[0].statistics().rays_total(), 0u);
}

TEST_F(LifecycleTest, ServerStatusReportsLimitsAndMethods) {
  const v1::ServerStatus st = server_status(stub());
  EXPECT_EQ(st.limits().max_sessions(), config_.limits.max_sessions);
  EXPECT_EQ(st.limits().max_pixels(), config_.limits.max_pixels);
  EXPECT_EQ(st.limits().max_frame_bytes(), service::max_frame_bytes(config_.limits.max_pixels));
  const std::vector<std::string> methods(st.methods().begin(), st.methods().end());
  EXPECT_EQ(methods, (std::vector<std::string>{"auto", "pt", "restir-gather", "restir-di", "restir-splat", "restir-splat-backup", "restir-multilayer"}));
  EXPECT_FALSE(st.draining());
  EXPECT_EQ(st.device(), service_context().device_name());
}

}  // namespace
}  // namespace strata::test
