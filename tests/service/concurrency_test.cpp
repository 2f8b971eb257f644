// One device shared by several sessions: concurrent sessions render exactly what each renders
// alone, and a session with expensive frames does not starve a cheap one.
#include <atomic>
#include <thread>

#include "harness.h"

namespace strata::test {
namespace {

using ConcurrencyTest = ServiceTest;

std::vector<std::string> raw_images(const std::vector<v1::Frame>& frames) {
  std::vector<std::string> out;
  for (const auto& f : frames) out.push_back(find_image(f, v1::IMAGE_ENCODING_RAW_RGBA16F)->data());
  return out;
}

TEST_F(ConcurrencyTest, TwoSessionsOnDifferentScenesRenderWhatEachRendersAlone) {
  constexpr uint32_t frames = 4;
  const auto req_a = session_request("cornell", 32, 24, 2, 11);
  const auto req_b = session_request("carousel", 40, 20, 1, 23);

  // Alone, one after the other.
  const v1::Session alone_a = create_ok(stub(), req_a);
  const auto a_alone = raw_images(stream_frames(stub(), alone_a.name(), frames));
  const v1::Session alone_b = create_ok(stub(), req_b);
  const auto b_alone = raw_images(stream_frames(stub(), alone_b.name(), frames));
  ASSERT_TRUE(delete_session(stub(), alone_a.name()).ok());
  ASSERT_TRUE(delete_session(stub(), alone_b.name()).ok());

  // Together: two clients streaming at once over their own channels.
  const v1::Session a = create_ok(stub(), req_a);
  const v1::Session b = create_ok(stub(), req_b);
  std::vector<std::string> a_together, b_together;
  std::thread ta([&] {
    auto stub_a = v1::RenderService::NewStub(loopback_channel(address()));
    a_together = raw_images(stream_frames(*stub_a, a.name(), frames));
  });
  std::thread tb([&] {
    auto stub_b = v1::RenderService::NewStub(loopback_channel(address()));
    b_together = raw_images(stream_frames(*stub_b, b.name(), frames));
  });
  ta.join();
  tb.join();
  ASSERT_EQ(a_together.size(), frames);
  ASSERT_EQ(b_together.size(), frames);
  for (uint32_t i = 0; i < frames; ++i) {
    EXPECT_TRUE(a_together[i] == a_alone[i]) << "cornell frame " << i << " differs when rendered next to another session";
    EXPECT_TRUE(b_together[i] == b_alone[i]) << "carousel frame " << i << " differs when rendered next to another session";
  }
  EXPECT_FALSE(a_alone[0] == a_alone[1]);
}

// Round-robin: while the expensive session renders one frame, the cheap one gets its turn too.
TEST_F(ConcurrencyTest, ASlowSessionDoesNotStarveAFastOne) {
  const v1::Session slow = create_ok(stub(), session_request("cornell", 160, 120, 16));
  const v1::Session fast = create_ok(stub(), session_request("cornell", 16, 12, 1));
  std::atomic<bool> stop{false};
  std::atomic<uint64_t> slow_frames{0}, fast_frames{0};
  auto run = [&](const v1::Session& s, std::atomic<uint64_t>& count) {
    auto st = v1::RenderService::NewStub(loopback_channel(address()));
    StreamClient c(*st);
    for (uint64_t i = 1; i <= 200 && !stop.load(); ++i) {
      if (!c.send(frame_input(i, i == 1 ? s.name() : "", uint32_t(i)))) break;
      if (!c.read()) break;
      count.fetch_add(1);
    }
    EXPECT_TRUE(c.close().ok());
  };
  std::thread ts([&] { run(slow, slow_frames); });
  std::thread tf([&] { run(fast, fast_frames); });
  // Until the slow session has rendered 4 frames (bounded).
  wait_until([&] { return slow_frames.load() >= 4; }, 60s);
  stop = true;
  ts.join();
  tf.join();
  ASSERT_GE(slow_frames.load(), 4u);
  // The fast session got at least one frame per slow frame (the queue alternates between them).
  EXPECT_GE(fast_frames.load() + 1, slow_frames.load()) << "fast " << fast_frames << " slow " << slow_frames;
}

}  // namespace
}  // namespace strata::test
