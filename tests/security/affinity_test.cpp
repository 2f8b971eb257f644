// Session affinity: CreateSession takes the client's session_id (AIP-133), refuses malformed ids
// with INVALID_ARGUMENT naming the field and the rule and a live id with ALREADY_EXISTS, and every
// response (errors and other services included) carries x-strata-instance.
#include "grpc/health/v1/health.grpc.pb.h"
#include "harness.h"

namespace strata::test {
namespace {

std::string instance_header(const grpc::ClientContext& ctx) {
  const auto& md = ctx.GetServerInitialMetadata();
  auto it = md.find("x-strata-instance");
  return it == md.end() ? "<none>" : std::string(it->second.data(), it->second.size());
}

class AffinityTest : public ServiceTest {
 protected:
  void SetUp() override {
    config_.instance_id = "daemon-a";
    ServiceTest::SetUp();
  }
};

TEST_F(AffinityTest, CreateSessionUsesTheClientsSessionId) {
  auto req = session_request("cornell", 16, 16);
  req.set_session_id("viewer-7-b");
  const auto s = create_ok(stub(), req);
  EXPECT_EQ(s.name(), "sessions/viewer-7-b");
  v1::Session got;
  ASSERT_TRUE(get_session(stub(), "sessions/viewer-7-b", &got).ok());
  const auto frames = stream_frames(stub(), s.name(), 2);
  EXPECT_EQ(frames.size(), 2u);
}

TEST_F(AffinityTest, AbsentSessionIdGetsAServerChosenOne) {
  const auto a = create_ok(stub(), session_request("cornell", 16, 16));
  const auto b = create_ok(stub(), session_request("cornell", 16, 16));
  EXPECT_EQ(a.name().rfind("sessions/", 0), 0u);
  EXPECT_NE(a.name(), b.name());
}

TEST_F(AffinityTest, DuplicateSessionIdIsAlreadyExistsAndLeavesTheFirstAlone) {
  auto req = session_request("cornell", 16, 16);
  req.set_session_id("dup");
  const auto first = create_ok(stub(), req);
  v1::Session second;
  const auto st = create_session(stub(), req, &second);
  EXPECT_EQ(st.error_code(), grpc::StatusCode::ALREADY_EXISTS) << st.error_message();
  EXPECT_NE(st.error_message().find("sessions/dup"), std::string::npos) << st.error_message();
  EXPECT_EQ(stream_frames(stub(), first.name(), 1).size(), 1u);  // the first one still works
  // Once deleted, the id may be used again.
  ASSERT_TRUE(delete_session(stub(), first.name()).ok());
  EXPECT_TRUE(create_session(stub(), req, &second).ok());
}

TEST_F(AffinityTest, MalformedSessionIdsAreInvalidArgumentNamingTheFieldAndRule) {
  const std::vector<std::pair<std::string, std::string>> cases = {
      {"Upper", "'U' at position 0"},
      {"a_b", "'_' at position 1"},
      {"7abc", "does not start with a letter"},
      {"abc-", "ends with '-'"},
      {std::string(64, 'a'), "has 64 characters"},
      {"a\x01" "b", "byte 1 at position 1"},
      {"sessions/x", "'/' at position 8"},
      {"caf\xc3\xa9", "byte 195 at position 3"},
  };
  for (const auto& [id, expected] : cases) {
    SCOPED_TRACE(id);
    auto req = session_request("cornell", 16, 16);
    req.set_session_id(id);
    v1::Session s;
    const auto st = create_session(stub(), req, &s);
    EXPECT_EQ(st.error_code(), grpc::StatusCode::INVALID_ARGUMENT);
    EXPECT_NE(st.error_message().find("session_id"), std::string::npos) << st.error_message();
    EXPECT_NE(st.error_message().find(expected), std::string::npos) << st.error_message();
    EXPECT_NE(st.error_message().find("1-63 characters"), std::string::npos) << st.error_message();
  }
  EXPECT_EQ(server_status(stub()).sessions(), 0u);
  auto ok = session_request("cornell", 16, 16);
  ok.set_session_id(std::string(63, 'z'));
  v1::Session s;
  EXPECT_TRUE(create_session(stub(), ok, &s).ok());
}

TEST_F(AffinityTest, EveryResponseCarriesTheInstanceId) {
  {
    grpc::ClientContext ctx;
    v1::ServerStatus st;
    ASSERT_TRUE(stub().GetServerStatus(&ctx, {}, &st).ok());
    EXPECT_EQ(instance_header(ctx), "daemon-a");
  }
  {  // an error
    grpc::ClientContext ctx;
    v1::GetSessionRequest req;
    req.set_name("sessions/nope");
    v1::Session s;
    EXPECT_EQ(stub().GetSession(&ctx, req, &s).error_code(), grpc::StatusCode::NOT_FOUND);
    EXPECT_EQ(instance_header(ctx), "daemon-a");
  }
  {  // a stream
    const auto s = create_ok(stub(), session_request("cornell", 16, 16));
    grpc::ClientContext ctx;
    auto rw = stub().Stream(&ctx);
    ASSERT_TRUE(rw->Write(frame_input(1, s.name())));
    v1::Frame f;
    ASSERT_TRUE(rw->Read(&f));
    EXPECT_EQ(instance_header(ctx), "daemon-a");
    rw->WritesDone();
    while (rw->Read(&f)) {
    }
    EXPECT_TRUE(rw->Finish().ok());
  }
  {  // another service
    auto health = grpc::health::v1::Health::NewStub(loopback_channel(address()));
    grpc::ClientContext ctx;
    grpc::health::v1::HealthCheckResponse resp;
    ASSERT_TRUE(health->Check(&ctx, {}, &resp).ok());
    EXPECT_EQ(instance_header(ctx), "daemon-a");
  }
}

TEST(InstanceIdTest, ABadInstanceIdIsRefused) {
  TempDir dir;
  auto config = test_config(dir.path);
  config.instance_id = "has space";
  EXPECT_THROW(service::Server(service_context(), config), std::invalid_argument);
}

}  // namespace
}  // namespace strata::test
