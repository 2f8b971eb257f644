// Streams ending: a client that goes away frees its session's device memory (and a new stream
// re-creates it, saying so); one stream per session; a deleted session ends its stream.
#include "harness.h"

namespace strata::test {
namespace {

using DisconnectTest = ServiceTest;

uint64_t session_memory(v1::RenderService::Stub& stub, const std::string& name, v1::Session::State* state = nullptr) {
  v1::Session s;
  EXPECT_TRUE(get_session(stub, name, &s).ok());
  if (state) *state = s.state();
  return s.memory().total_bytes();
}

TEST_F(DisconnectTest, ClientDisconnectFreesTheSessionsDeviceMemory) {
  const v1::Session s = create_ok(stub(), session_request("carousel", 64, 48));
  ASSERT_GT(s.memory().total_bytes(), 0u);
  {
    StreamClient c(stub());
    ASSERT_TRUE(c.send(frame_input(1, s.name(), 0)));
    ASSERT_TRUE(c.read());
    v1::Session::State state;
    EXPECT_GT(session_memory(stub(), s.name(), &state), 0u);
    EXPECT_EQ(state, v1::Session::STREAMING);
    EXPECT_GT(server_status(stub()).device_memory_bytes(), 0u);
    c.cancel();  // the client goes away without closing
    EXPECT_EQ(c.finish().error_code(), grpc::StatusCode::CANCELLED);
  }
  ASSERT_TRUE(wait_until([&] { return session_memory(stub(), s.name()) == 0; }, 10s)) << "device memory was not freed";
  v1::Session::State state;
  session_memory(stub(), s.name(), &state);
  EXPECT_EQ(state, v1::Session::IDLE);
  EXPECT_EQ(server_status(stub()).device_memory_bytes(), 0u);

  // A new stream re-creates the GPU state and says so.
  StreamClient again(stub());
  ASSERT_TRUE(again.send(frame_input(1, s.name(), 1)));
  auto f = again.read();
  ASSERT_TRUE(f);
  EXPECT_TRUE(f->history_reset());
  EXPECT_NE(f->history_reset_reason().find("released"), std::string::npos) << f->history_reset_reason();
  EXPECT_EQ(f->frame_index(), 1u);
  EXPECT_GT(session_memory(stub(), s.name()), 0u);
  EXPECT_TRUE(again.close().ok());
}

TEST_F(DisconnectTest, ASecondStreamOnABusySessionIsAborted) {
  const v1::Session s = create_ok(stub(), session_request("cornell", 16, 12));
  StreamClient first(stub());
  ASSERT_TRUE(first.send(frame_input(1, s.name(), 0)));
  ASSERT_TRUE(first.read());

  StreamClient second(stub());
  second.send(frame_input(1, s.name(), 0));
  EXPECT_FALSE(second.read());
  const grpc::Status st = second.finish();
  EXPECT_EQ(st.error_code(), grpc::StatusCode::ABORTED);
  EXPECT_NE(st.error_message().find("already has a stream attached"), std::string::npos) << st.error_message();

  // The first stream goes on.
  ASSERT_TRUE(first.send(frame_input(2, "", 1)));
  auto f = first.read();
  ASSERT_TRUE(f);
  EXPECT_EQ(f->input_sequence(), 2u);
  EXPECT_TRUE(first.close().ok());
}

TEST_F(DisconnectTest, DeletingASessionEndsItsStreamWithNotFound) {
  const v1::Session s = create_ok(stub(), session_request("cornell", 16, 12));
  StreamClient c(stub());
  ASSERT_TRUE(c.send(frame_input(1, s.name(), 0)));
  ASSERT_TRUE(c.read());
  ASSERT_TRUE(delete_session(stub(), s.name()).ok());
  EXPECT_TRUE(wait_until([&] { return !c.read().has_value(); }, 10s));
  const grpc::Status st = c.finish();
  EXPECT_EQ(st.error_code(), grpc::StatusCode::NOT_FOUND);
  EXPECT_NE(st.error_message().find("was deleted"), std::string::npos) << st.error_message();
  EXPECT_TRUE(wait_until([&] { return server_status(stub()).streams() == 0; }, 10s));
  EXPECT_EQ(server_status(stub()).device_memory_bytes(), 0u);
}

}  // namespace
}  // namespace strata::test
