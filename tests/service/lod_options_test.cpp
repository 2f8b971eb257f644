// The LoD-aware reuse options over gRPC (render.proto lod_mapping, lod_matching, lod_vertices): the
// session's decisions say whether tau maps points and why, the options reach the renderer (a
// LoD-group scene with history reports the UV structure's memory), and bad values are refused.
#include "harness.h"

namespace strata::test {
namespace {

using LodOptionsTest = ServiceTest;

v1::CreateSessionRequest request(const std::string& scene, const std::string& method) {
  auto req = session_request(scene, 16, 16);
  req.set_method(method);
  return req;
}

TEST_F(LodOptionsTest, DecisionsSayWhereTauMaps) {
  const v1::Session auto_uv = create_ok(stub(), request("lod-cliff", "restir-splat"));
  const v1::Decision* d = decision(auto_uv, "lod_mapping");
  ASSERT_NE(d, nullptr);
  EXPECT_EQ(d->requested(), "");
  EXPECT_EQ(d->value(), "uv");
  EXPECT_TRUE(d->applies());
  EXPECT_NE(d->reason().find("UV parametrisation"), std::string::npos) << d->reason();
  EXPECT_EQ(decision(auto_uv, "lod_matching")->value(), "true");
  EXPECT_EQ(decision(auto_uv, "lod_vertices")->value(), "both");
  EXPECT_GT(auto_uv.memory().bytes_by_group().at("lod_uv_space"), 0u);

  auto off_req = request("lod-cliff", "restir-splat");
  off_req.mutable_options()->set_lod_mapping(v1::LOD_MAPPING_OFF);
  off_req.mutable_options()->mutable_experimental()->set_lod_vertices(v1::LOD_VERTICES_PRIMARY);
  off_req.mutable_options()->mutable_experimental()->set_lod_matching(false);
  const v1::Session off = create_ok(stub(), off_req);
  EXPECT_EQ(decision(off, "lod_mapping")->value(), "off");
  EXPECT_FALSE(decision(off, "lod_mapping")->applies());
  EXPECT_NE(decision(off, "lod_mapping")->reason().find("refuses"), std::string::npos);
  EXPECT_EQ(decision(off, "lod_vertices")->value(), "primary");
  EXPECT_FALSE(decision(off, "lod_vertices")->applies());
  EXPECT_EQ(off.options().experimental().lod_matching(), false);

  const v1::Session cornell = create_ok(stub(), request("cornell", "restir-splat"));
  EXPECT_EQ(decision(cornell, "lod_mapping")->value(), "off");
  EXPECT_NE(decision(cornell, "lod_mapping")->reason().find("no instance with LoD levels"), std::string::npos);
  EXPECT_FALSE(cornell.memory().bytes_by_group().contains("lod_uv_space"));

  const v1::Session pt = create_ok(stub(), request("lod-cliff", "pt"));
  EXPECT_EQ(decision(pt, "lod_mapping")->value(), "off");
  EXPECT_FALSE(pt.memory().bytes_by_group().contains("lod_uv_space"));
}

TEST_F(LodOptionsTest, UnknownLodVerticesIsRefusedNamingTheField) {
  auto req = request("lod-cliff", "restir-splat");
  req.mutable_options()->mutable_experimental()->set_lod_vertices(static_cast<v1::LodVertices>(9));
  v1::Session s;
  const grpc::Status st = create_session(stub(), req, &s);
  EXPECT_EQ(st.error_code(), grpc::StatusCode::INVALID_ARGUMENT);
  EXPECT_NE(st.error_message().find("lod_vertices = 9 is not one of"), std::string::npos) << st.error_message();
}

}  // namespace
}  // namespace strata::test
