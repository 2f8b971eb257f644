// Idle expiry: a session without a stream expires after idle_timeout (NOT_FOUND says so); a
// session with a stream attached does not.
#include "harness.h"

namespace strata::test {
namespace {

class ExpiryTest : public ServiceTest {
 protected:
  void SetUp() override {
    config_.idle_timeout = 400ms;
    ServiceTest::SetUp();
  }
  // ListSessions does not count as activity (GetSession does).
  bool listed(const std::string& name) {
    grpc::ClientContext ctx;
    v1::ListSessionsResponse resp;
    EXPECT_TRUE(stub().ListSessions(&ctx, {}, &resp).ok());
    for (const auto& s : resp.sessions())
      if (s.name() == name) return true;
    return false;
  }
};

TEST_F(ExpiryTest, AnIdleSessionExpires) {
  const v1::Session s = create_ok(stub(), session_request("cornell", 16, 12));
  EXPECT_TRUE(listed(s.name()));
  ASSERT_TRUE(wait_until([&] { return !listed(s.name()); }, 10s)) << "the idle session did not expire";
  v1::Session got;
  const grpc::Status st = get_session(stub(), s.name(), &got);
  EXPECT_EQ(st.error_code(), grpc::StatusCode::NOT_FOUND);
  EXPECT_NE(st.error_message().find("expired after 400 ms idle"), std::string::npos) << st.error_message();
  const v1::ServerStatus status = server_status(stub());
  EXPECT_EQ(status.sessions_expired(), 1u);
  EXPECT_EQ(status.device_memory_bytes(), 0u);

  StreamClient c(stub());
  c.send(frame_input(1, s.name(), 0));
  EXPECT_FALSE(c.read());
  EXPECT_EQ(c.finish().error_code(), grpc::StatusCode::NOT_FOUND);
}

TEST_F(ExpiryTest, AStreamingSessionDoesNotExpireAndExpiresAfterItsStreamEnds) {
  const v1::Session s = create_ok(stub(), session_request("cornell", 16, 12));
  {
    StreamClient c(stub());
    const auto start = std::chrono::steady_clock::now();
    uint64_t i = 1;
    // Three idle timeouts long, with frames now and then.
    for (; std::chrono::steady_clock::now() - start < 1200ms && i < 1000; ++i) {
      ASSERT_TRUE(c.send(frame_input(i, i == 1 ? s.name() : "", uint32_t(i))));
      ASSERT_TRUE(c.read()) << "the stream ended while streaming";
      std::this_thread::sleep_for(100ms);
    }
    std::this_thread::sleep_for(600ms);  // attached but quiet, longer than idle_timeout
    EXPECT_TRUE(listed(s.name()));
    ASSERT_TRUE(c.send(frame_input(i, "", 0)));
    EXPECT_TRUE(c.read());
    EXPECT_TRUE(c.close().ok());
  }
  EXPECT_TRUE(wait_until([&] { return !listed(s.name()); }, 10s)) << "did not expire after the stream ended";
}

}  // namespace
}  // namespace strata::test
