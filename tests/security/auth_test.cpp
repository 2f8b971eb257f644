// Bearer tokens on a plaintext server: every RPC of strata.v1.RenderService is UNAUTHENTICATED
// without the token or with a wrong one, works with it, and health stays open for probes.
#include <fstream>

#include "grpc/health/v1/health.grpc.pb.h"
#include "harness.h"
#include "service/auth_token.h"

namespace strata::test {
namespace {

constexpr const char* k_token = "s3cret-token-0123456789abcdef";

std::shared_ptr<grpc::Channel> channel_with(const std::string& address) { return loopback_channel(address); }

void authorize(grpc::ClientContext& ctx, const std::string& value) {
  if (!value.empty()) ctx.AddMetadata("authorization", value);
}

// Calls every RenderService method once with the `authorization` value (empty: none) and returns
// each call's status code by method name. Stream: the status its Finish returns.
std::map<std::string, grpc::StatusCode> call_every_method(v1::RenderService::Stub& stub, const std::string& auth) {
  std::map<std::string, grpc::StatusCode> out;
  auto unary = [&](const std::string& name, auto&& call) {
    grpc::ClientContext ctx;
    ctx.set_deadline(std::chrono::system_clock::now() + 30s);
    authorize(ctx, auth);
    out[name] = call(ctx).error_code();
  };
  auto create = session_request("cornell", 16, 16);
  v1::Session session;
  unary("CreateSession", [&](grpc::ClientContext& c) { return stub.CreateSession(&c, create, &session); });
  v1::GetSessionRequest get;
  get.set_name(session.name().empty() ? "sessions/none" : session.name());
  unary("GetSession", [&](grpc::ClientContext& c) { return stub.GetSession(&c, get, &session); });
  v1::ListSessionsResponse list;
  unary("ListSessions", [&](grpc::ClientContext& c) { return stub.ListSessions(&c, {}, &list); });
  v1::ListScenesResponse scenes;
  unary("ListScenes", [&](grpc::ClientContext& c) { return stub.ListScenes(&c, {}, &scenes); });
  v1::ServerStatus status;
  unary("GetServerStatus", [&](grpc::ClientContext& c) { return stub.GetServerStatus(&c, {}, &status); });
  v1::ReferenceRequest ref;
  ref.mutable_scene()->set_builtin("cornell");
  ref.mutable_resolution()->set_width(8);
  ref.mutable_resolution()->set_height(8);
  ref.set_spp(1);
  ref.set_max_depth(4);
  ref.mutable_frame()->set_animation_frame(0);
  ref.set_encoding(v1::IMAGE_ENCODING_RAW_RGBA16F);
  v1::Reference reference;
  unary("RenderReference", [&](grpc::ClientContext& c) { return stub.RenderReference(&c, ref, &reference); });
  {
    grpc::ClientContext ctx;
    ctx.set_deadline(std::chrono::system_clock::now() + 30s);
    authorize(ctx, auth);
    auto rw = stub.Stream(&ctx);
    rw->Write(frame_input(1, get.name()));
    rw->WritesDone();
    v1::Frame f;
    while (rw->Read(&f)) {
    }
    out["Stream"] = rw->Finish().error_code();
  }
  google::protobuf::Empty empty;
  v1::DeleteSessionRequest del;
  del.set_name(get.name());
  unary("DeleteSession", [&](grpc::ClientContext& c) { return stub.DeleteSession(&c, del, &empty); });
  return out;
}

class AuthTest : public ServiceTest {
 protected:
  void SetUp() override {
    std::ofstream(token_dir_.path / "token") << k_token << "\n";  // a final newline is not part of it
    config_.security.auth_token_file = token_dir_.path / "token";
    config_.reference_cache = token_dir_.path / "references";  // not the user's cache
    ServiceTest::SetUp();
  }
  TempDir token_dir_;
};

TEST_F(AuthTest, EveryRenderServiceMethodIsCovered) {
  // When an RPC is added, it must be gated in service/auth_gate.cpp and called above.
  const auto* service = v1::RenderService::service_full_name();
  const auto* desc = google::protobuf::DescriptorPool::generated_pool()->FindServiceByName(service);
  ASSERT_NE(desc, nullptr);
  const auto calls = call_every_method(stub(), "Bearer " + std::string(k_token));
  ASSERT_EQ(size_t(desc->method_count()), calls.size());
  for (int i = 0; i < desc->method_count(); ++i) EXPECT_TRUE(calls.count(desc->method(i)->name())) << desc->method(i)->name();
}

TEST_F(AuthTest, WithoutATokenEveryMethodIsUnauthenticated) {
  for (const auto& [method, code] : call_every_method(stub(), "")) EXPECT_EQ(code, grpc::StatusCode::UNAUTHENTICATED) << method;
  EXPECT_EQ(server_->core().registry.size(), 0u);  // nothing was created on the way
}

TEST_F(AuthTest, WrongOrMalformedTokensAreUnauthenticated) {
  for (const std::string& auth : std::vector<std::string>{"Bearer wrong-token-0123456789abcdef", "Bearer " + std::string(k_token) + "x",
                                 "Bearer " + std::string(k_token).substr(1), std::string(k_token), "Basic " + std::string(k_token),
                                 std::string("Bearer ")}) {
    SCOPED_TRACE(auth);
    for (const auto& [method, code] : call_every_method(stub(), auth)) EXPECT_EQ(code, grpc::StatusCode::UNAUTHENTICATED) << method;
  }
  EXPECT_EQ(server_->core().registry.size(), 0u);
}

TEST_F(AuthTest, TheRightTokenWorks) {
  const auto calls = call_every_method(stub(), "Bearer " + std::string(k_token));
  for (const auto& [method, code] : calls) {
    // The stream's session exists, the stream ends OK after WritesDone.
    EXPECT_EQ(code, grpc::StatusCode::OK) << method;
  }
}

TEST_F(AuthTest, UnauthenticatedMessagesDoNotEchoTheToken) {
  grpc::ClientContext ctx;
  authorize(ctx, "Bearer guess-guess-guess-guess");
  v1::ServerStatus status;
  const auto st = stub().GetServerStatus(&ctx, {}, &status);
  EXPECT_EQ(st.error_code(), grpc::StatusCode::UNAUTHENTICATED);
  EXPECT_EQ(st.error_message().find("guess"), std::string::npos) << st.error_message();
  EXPECT_EQ(st.error_message().find(k_token), std::string::npos) << st.error_message();
}

TEST_F(AuthTest, HealthNeedsNoToken) {
  auto health = grpc::health::v1::Health::NewStub(channel_with(address()));
  grpc::ClientContext ctx;
  grpc::health::v1::HealthCheckResponse resp;
  ASSERT_TRUE(health->Check(&ctx, {}, &resp).ok());
  EXPECT_EQ(resp.status(), grpc::health::v1::HealthCheckResponse::SERVING);
}

TEST(BearerTokenTest, UnusableTokenFilesAreRefusedNamingTheFlag) {
  TempDir dir;
  std::ofstream(dir.path / "short") << "abc\n";
  std::ofstream(dir.path / "spaces") << "abc def ghi jkl mno pqr\n";
  for (const auto& name : {"short", "spaces", "missing"}) {
    SCOPED_TRACE(name);
    try {
      service::BearerToken::load(dir.path / name);
      ADD_FAILURE() << "accepted";
    } catch (const std::invalid_argument& e) {
      EXPECT_NE(std::string(e.what()).find("--auth-token-file"), std::string::npos) << e.what();
    }
  }
}

TEST(BearerTokenTest, ConstantTimeEqualIsEquality) {
  EXPECT_TRUE(service::constant_time_equal("abc", "abc"));
  EXPECT_FALSE(service::constant_time_equal("abc", "abd"));
  EXPECT_FALSE(service::constant_time_equal("abc", "abcd"));
  EXPECT_FALSE(service::constant_time_equal("", "a"));
  EXPECT_TRUE(service::constant_time_equal("", ""));
}

}  // namespace
}  // namespace strata::test
