// RenderReference through the in-process server: every bad request answered with its status and
// a message naming the field and the limit while another session keeps streaming; references
// accumulate to the target spp or stop early at the target error, come from the cache the second
// time, and a corrupt cache entry is rendered again; an open shutter blurs a moving camera, in a
// reference as in a stream.
#include <algorithm>
#include <cmath>
#include <fstream>
#include <limits>
#include <thread>

#include "harness.h"
#include "image/image.h"

namespace strata::test {
namespace {

using grpc::StatusCode;

class ReferenceTest : public ServiceTest {
 protected:
  void SetUp() override {
    ServiceTest::SetUp();
    auto c = test_config(scene_dir_.path);
    c.limits.max_reference_spp = 512;
    c.reference_cache = cache_dir_.path;
    start(c);
  }

  static v1::ReferenceRequest ok_request(uint32_t spp = 8) {
    v1::ReferenceRequest r;
    r.mutable_scene()->set_builtin("cornell");
    r.mutable_resolution()->set_width(8);
    r.mutable_resolution()->set_height(6);
    r.mutable_frame()->set_animation_frame(0);
    r.set_spp(spp);
    r.set_seed(3);
    r.set_encoding(v1::IMAGE_ENCODING_RAW_RGBA16F);
    return r;
  }

  grpc::Status reference(const v1::ReferenceRequest& req, v1::Reference* out) {
    grpc::ClientContext ctx;
    ctx.set_deadline(std::chrono::system_clock::now() + 120s);
    return stub().RenderReference(&ctx, req, out);
  }

  // A camera at x looking down -Z (over carousel from its side), with a shutter.
  static v1::Camera moving_camera(float x, float shutter) {
    v1::Camera c;
    c.mutable_position()->set_x(x);
    c.mutable_position()->set_y(1.6f);
    c.mutable_position()->set_z(6.0f);
    c.mutable_orientation()->set_w(1.0f);
    c.set_vertical_fov(0.8f);
    c.set_shutter(shutter);
    return c;
  }

  // Carousel at 32x32, 64 spp: the camera at x = 0 with `shutter`, the previous frame's at
  // `previous_x` (the objects as in animation frame 0).
  static v1::ReferenceRequest blur_request(float shutter, float previous_x, uint32_t seed) {
    v1::ReferenceRequest r = ok_request(64);
    r.mutable_scene()->set_builtin("carousel");
    r.mutable_resolution()->set_width(32);
    r.mutable_resolution()->set_height(32);
    r.set_seed(seed);
    *r.mutable_frame()->mutable_camera() = moving_camera(0.0f, shutter);
    r.mutable_previous_frame()->set_animation_frame(0);
    *r.mutable_previous_frame()->mutable_camera() = moving_camera(previous_x, 0.0f);
    return r;
  }

  static image::Image decoded(const v1::Reference& r) {
    const auto& d = r.image().data();
    return image::decode_rgba16f(std::vector<uint8_t>(d.begin(), d.end()), r.image().width(), r.image().height());
  }

  TempDir cache_dir_;
};

TEST_F(ReferenceTest, EveryBadRequestGetsItsStatusAndMessage) {
  const v1::Session other = create_ok(stub(), session_request("carousel", 24, 16));
  BackgroundStream background(address(), other.name());
  ASSERT_TRUE(wait_until([&] { return background.frames() >= 2; }, 30s));

  const float nan = std::numeric_limits<float>::quiet_NaN();
  const auto invalid = StatusCode::INVALID_ARGUMENT;
  struct Case {
    std::string what;
    std::function<void(v1::ReferenceRequest&)> edit;
    StatusCode code;
    std::string message;
  };
  const std::vector<Case> cases = {
      {"no scene", [](auto& r) { r.clear_scene(); }, invalid, "scene is required"},
      {"unknown built-in", [](auto& r) { r.mutable_scene()->set_builtin("nope"); }, invalid,
       "scene.builtin = 'nope' is not a built-in scene; built-in scenes: cornell"},
      {"missing scene file", [](auto& r) { r.mutable_scene()->set_path("missing.glb"); }, StatusCode::NOT_FOUND,
       "scene.path = 'missing.glb' does not exist"},
      {"no resolution", [](auto& r) { r.clear_resolution(); }, invalid, "resolution is required"},
      {"zero width", [](auto& r) { r.mutable_resolution()->set_width(0); }, invalid,
       "resolution.width = 0 is outside [1, 1024] (max_dimension)"},
      {"height over max_dimension", [](auto& r) { r.mutable_resolution()->set_height(5000); }, invalid,
       "resolution.height = 5000 is outside [1, 1024] (max_dimension)"},
      {"over max_pixels", [](auto& r) { r.mutable_resolution()->set_width(1024); r.mutable_resolution()->set_height(1024); },
       invalid, "exceeds max_pixels = 307200"},
      {"no frame", [](auto& r) { r.clear_frame(); }, invalid, "frame is required"},
      {"spp 0", [](auto& r) { r.set_spp(0); }, invalid, "spp = 0 is outside [1, 512] (max_reference_spp)"},
      {"spp over the limit", [](auto& r) { r.set_spp(513); }, invalid, "spp = 513 is outside [1, 512] (max_reference_spp)"},
      {"max_depth over the limit", [](auto& r) { r.set_max_depth(33); }, invalid, "max_depth = 33 is outside [1, 32]"},
      {"NaN relative error", [&](auto& r) { r.set_relative_error(nan); }, invalid, "relative_error = nan is outside [0, 1)"},
      {"relative error 1", [](auto& r) { r.set_relative_error(1.0f); }, invalid, "relative_error = 1 is outside [0, 1)"},
      {"PNG encoding", [](auto& r) { r.set_encoding(v1::IMAGE_ENCODING_PNG_PREVIEW); }, invalid,
       "encoding = PNG_PREVIEW is not an HDR encoding"},
      {"NaN camera", [&](auto& r) {
         auto* c = r.mutable_frame()->mutable_camera();
         c->mutable_position()->set_x(nan);
         c->mutable_orientation()->set_w(1.0f);
         c->set_vertical_fov(0.8f);
       }, invalid, "frame.camera.position.x = nan is not finite"},
      {"camera without orientation", [](auto& r) {
         r.mutable_frame()->mutable_camera()->mutable_position()->set_z(3.0f);
         r.mutable_frame()->mutable_camera()->set_vertical_fov(0.8f);
       }, invalid, "frame.camera.orientation is required"},
      {"unknown instance", [](auto& r) {
         auto* t = r.mutable_frame()->add_transforms();
         t->set_instance_id(999);
       }, invalid, "frame.transforms[0].instance_id = 999 is not an instance id"},
      {"LoD level out of range", [](auto& r) {
         auto* l = r.mutable_frame()->add_lod_changes();
         l->set_instance_id(0);
         l->set_level(50);
       }, invalid, "frame.lod_changes[0].level = 50 is out of range"},
      {"shutter over 1", [](auto& r) {
         *r.mutable_frame()->mutable_camera() = moving_camera(0.0f, 2.0f);
         r.mutable_previous_frame()->set_animation_frame(0);
       }, invalid, "frame.camera.shutter = 2 is outside [0, 1]"},
      {"open shutter without previous frame", [](auto& r) { *r.mutable_frame()->mutable_camera() = moving_camera(0.0f, 0.5f); },
       invalid, "previous_frame is required when frame.camera.shutter = 0.5 > 0: the shutter opens on the way from the "
                "previous frame's camera"},
      {"bad previous frame", [&](auto& r) {
         auto* c = r.mutable_previous_frame()->mutable_camera();
         c->mutable_position()->set_y(std::numeric_limits<float>::infinity());
         c->mutable_orientation()->set_w(1.0f);
         c->set_vertical_fov(0.8f);
       }, invalid, "previous_frame.camera.position.y = inf is not finite"},
  };
  const uint64_t before = background.frames();
  for (const auto& c : cases) {
    v1::ReferenceRequest r = ok_request();
    c.edit(r);
    v1::Reference out;
    const grpc::Status st = reference(r, &out);
    EXPECT_EQ(st.error_code(), c.code) << c.what << ": " << st.error_message();
    EXPECT_NE(st.error_message().find(c.message), std::string::npos)
        << c.what << ": message '" << st.error_message() << "' does not contain '" << c.message << "'";
  }
  ASSERT_TRUE(wait_until([&] { return background.frames() > before + 2; }, 30s));
  const grpc::Status bg = background.stop();
  EXPECT_TRUE(bg.ok()) << bg.error_message();
  EXPECT_EQ(server_status(stub()).limits().max_reference_spp(), 512u);
}

TEST_F(ReferenceTest, RendersThenAnswersFromTheCacheAndRerendersACorruptEntry) {
  v1::Reference first;
  ASSERT_TRUE(reference(ok_request(16), &first).ok());
  EXPECT_FALSE(first.cached());
  EXPECT_EQ(first.spp(), 16u);
  EXPECT_EQ(first.batches(), 16u);  // 1 spp per batch below 32 spp
  EXPECT_EQ(first.scene(), "cornell");
  EXPECT_EQ(first.cache_key().size(), 64u);
  EXPECT_GT(first.gpu_ms(), 0.0);
  EXPECT_GT(first.relative_error(), 0.0);
  EXPECT_TRUE(std::isfinite(first.relative_error()));
  EXPECT_TRUE(first.disoccluded_mask().empty());  // no previous frame state asked for
  const image::Image img = decoded(first);
  ASSERT_EQ(img.width, 8u);
  ASSERT_EQ(img.height, 6u);
  double sum = 0.0;
  for (float v : img.rgba) {
    ASSERT_TRUE(std::isfinite(v));
    sum += v;
  }
  EXPECT_GT(sum, 0.0);
  const std::filesystem::path entry = cache_dir_.path / (first.cache_key() + ".ref");
  EXPECT_TRUE(std::filesystem::exists(entry));

  v1::Reference second;
  ASSERT_TRUE(reference(ok_request(16), &second).ok());
  EXPECT_TRUE(second.cached());
  EXPECT_EQ(second.cache_key(), first.cache_key());
  EXPECT_EQ(second.image().data(), first.image().data());
  EXPECT_EQ(second.relative_error(), first.relative_error());
  EXPECT_EQ(second.gpu_ms(), first.gpu_ms());

  // A corrupt entry is rendered again (the same image: the random streams are the same).
  {
    std::fstream f(entry, std::ios::in | std::ios::out | std::ios::binary);
    f.seekg(200);
    const char c = char(f.get());
    f.seekp(200);
    f.put(char(c ^ 0x5a));
  }
  v1::Reference third;
  ASSERT_TRUE(reference(ok_request(16), &third).ok());
  EXPECT_FALSE(third.cached());
  EXPECT_EQ(third.image().data(), first.image().data());
  v1::Reference fourth;
  ASSERT_TRUE(reference(ok_request(16), &fourth).ok());
  EXPECT_TRUE(fourth.cached());

  // Another frame state, seed or setting is another entry; EXR is the default encoding.
  v1::ReferenceRequest moved = ok_request(16);
  moved.set_seed(4);
  moved.clear_encoding();
  moved.mutable_previous_frame()->set_animation_frame(0);  // does not change the image
  v1::Reference other;
  ASSERT_TRUE(reference(moved, &other).ok());
  EXPECT_FALSE(other.cached());
  EXPECT_NE(other.cache_key(), first.cache_key());
  EXPECT_EQ(other.image().encoding(), v1::IMAGE_ENCODING_EXR_HALF);
  // With a previous frame state the mask comes back, width*height bytes of 0 or 1 (cornell's
  // camera is still: nothing is disoccluded), for a rendered and for a cached reference alike.
  ASSERT_EQ(other.disoccluded_mask().size(), 8u * 6u);
  for (char c : other.disoccluded_mask()) EXPECT_EQ(c, 0);
  v1::Reference other_cached;
  ASSERT_TRUE(reference(moved, &other_cached).ok());
  EXPECT_TRUE(other_cached.cached());
  EXPECT_EQ(other_cached.disoccluded_mask(), other.disoccluded_mask());
}

// Relative L1 difference of two images' means over 8x8-pixel blocks (the blocks average the noise
// away, so that what remains is where the images' content differs).
double block_difference(const image::Image& a, const image::Image& b) {
  double diff = 0.0, sum = 0.0;
  for (uint32_t by = 0; by < a.height; by += 8)
    for (uint32_t bx = 0; bx < a.width; bx += 8)
      for (uint32_t c = 0; c < 3; ++c) {
        double ma = 0.0, mb = 0.0;
        for (uint32_t y = by; y < std::min(by + 8, a.height); ++y)
          for (uint32_t x = bx; x < std::min(bx + 8, a.width); ++x) {
            ma += a.rgba[4 * (size_t(y) * a.width + x) + c];
            mb += b.rgba[4 * (size_t(y) * b.width + x) + c];
          }
        diff += std::fabs(ma - mb);
        sum += ma;
      }
  return diff / sum;
}

// Motion blur (RS-main 4.4): with the shutter open over a 3 m pan from the previous frame's
// camera, the reference is the mean over the shutter, another image and cache entry than the
// instant's; an open shutter on a camera that does not move renders the instant.
TEST_F(ReferenceTest, AnOpenShutterBlursAMovingCamera) {
  v1::Reference sharp, sharp_other_seed, blurred, still;
  ASSERT_TRUE(reference(blur_request(0.0f, -3.0f, 5), &sharp).ok());
  ASSERT_TRUE(reference(blur_request(0.0f, -3.0f, 6), &sharp_other_seed).ok());
  const grpc::Status st = reference(blur_request(1.0f, -3.0f, 5), &blurred);
  ASSERT_TRUE(st.ok()) << st.error_message();
  ASSERT_TRUE(reference(blur_request(1.0f, 0.0f, 5), &still).ok());
  EXPECT_NE(blurred.cache_key(), sharp.cache_key());
  EXPECT_NE(still.cache_key(), sharp.cache_key()) << "the camera's shutter is in the key";
  EXPECT_EQ(still.image().data(), sharp.image().data()) << "a still camera's open shutter renders the instant";
  const double noise = block_difference(decoded(sharp), decoded(sharp_other_seed));
  const double blur = block_difference(decoded(sharp), decoded(blurred));
  EXPECT_GT(blur, 4.0 * noise) << "blurred vs sharp " << blur << ", two seeds of the sharp image " << noise;

  v1::Reference again;
  ASSERT_TRUE(reference(blur_request(1.0f, -3.0f, 5), &again).ok());
  EXPECT_TRUE(again.cached());
  EXPECT_EQ(again.image().data(), blurred.image().data());
}

// A stream opens its shutter on the way from the camera of the frame it rendered before (none
// for its first frame: an instant), as RenderReference does from previous_frame: the stream's
// frame matches the blurred reference, not the sharp one.
TEST_F(ReferenceTest, AStreamBlursLikeItsReference) {
  const v1::Session s = create_ok(stub(), session_request("carousel", 32, 32, 64, 9));
  StreamClient stream(stub());
  std::optional<v1::Frame> last;
  for (uint64_t i = 1; i <= 2; ++i) {
    v1::FrameInput in = frame_input(i, i == 1 ? s.name() : "", 0);
    *in.mutable_camera() = moving_camera(i == 1 ? -3.0f : 0.0f, 1.0f);
    ASSERT_TRUE(stream.send(in));
    last = stream.read();
    ASSERT_TRUE(last.has_value());
  }
  const grpc::Status closed = stream.close();
  ASSERT_TRUE(closed.ok()) << closed.error_message();
  v1::Reference blurred, sharp;
  ASSERT_TRUE(reference(blur_request(1.0f, -3.0f, 5), &blurred).ok());
  ASSERT_TRUE(reference(blur_request(0.0f, -3.0f, 5), &sharp).ok());
  const image::Image frame = frame_image(*last);
  const double to_blurred = block_difference(decoded(blurred), frame), to_sharp = block_difference(decoded(sharp), frame);
  EXPECT_LT(to_blurred, 0.5 * to_sharp) << "stream vs blurred reference " << to_blurred << ", vs sharp " << to_sharp;
}

TEST_F(ReferenceTest, StopsEarlyAtTheTargetError) {
  v1::ReferenceRequest r = ok_request(512);
  r.set_relative_error(0.9f);  // reached after the minimum number of batches
  v1::Reference out;
  ASSERT_TRUE(reference(r, &out).ok());
  EXPECT_TRUE(out.relative_error_reached());
  EXPECT_LT(out.spp(), 512u);
  EXPECT_GE(out.batches(), 8u);
  EXPECT_LE(out.relative_error(), 0.9);

  // The estimate falls as samples accumulate (about as 1/sqrt(spp)).
  v1::Reference few, many;
  ASSERT_TRUE(reference(ok_request(16), &few).ok());
  ASSERT_TRUE(reference(ok_request(256), &many).ok());
  EXPECT_FALSE(many.relative_error_reached());
  EXPECT_EQ(many.spp(), 256u);
  EXPECT_LT(many.relative_error(), few.relative_error() * 0.5);
}

TEST_F(ReferenceTest, LongReferencesAreBoundedCancellableAndDrained) {
  // Long references (64x64 at 512 spp: 16 batches of 32) fill the server's max_sessions = 4.
  auto long_request = [](uint32_t seed) {
    v1::ReferenceRequest r = ok_request(512);
    r.mutable_resolution()->set_width(64);
    r.mutable_resolution()->set_height(64);
    r.set_seed(seed);
    return r;
  };
  const uint64_t rounds_before = server_->core().scheduler.rounds();
  struct Call {
    grpc::ClientContext ctx;
    grpc::Status status;
    std::thread thread;
  };
  std::vector<std::unique_ptr<Call>> calls;
  for (uint32_t i = 0; i < config_.limits.max_sessions; ++i) {
    auto c = std::make_unique<Call>();
    c->ctx.set_deadline(std::chrono::system_clock::now() + 120s);
    c->thread = std::thread([this, c = c.get(), r = long_request(100 + i)] {
      v1::Reference out;
      c->status = stub().RenderReference(&c->ctx, r, &out);
    });
    calls.push_back(std::move(c));
  }
  // Batches of all four take turns on the scheduler.
  ASSERT_TRUE(wait_until([&] { return server_->core().scheduler.rounds() >= rounds_before + 8; }, 60s));
  v1::Reference out;
  grpc::Status st = reference(long_request(7), &out);
  EXPECT_EQ(st.error_code(), StatusCode::RESOURCE_EXHAUSTED) << st.error_message();
  EXPECT_NE(st.error_message().find("at most max_sessions = 4 at once"), std::string::npos) << st.error_message();
  // Sessions still get their frames meanwhile.
  const v1::Session s = create_ok(stub(), session_request("cornell", 16, 16));
  EXPECT_EQ(stream_frames(stub(), s.name(), 2).size(), 2u);

  // Cancelled calls stop their accumulation: the scheduler goes idle.
  for (auto& c : calls) c->ctx.TryCancel();
  for (auto& c : calls) {
    c->thread.join();
    EXPECT_EQ(c->status.error_code(), StatusCode::CANCELLED) << c->status.error_message();
  }
  ASSERT_TRUE(server_->core().scheduler.wait_idle(10s));
  const uint64_t idle_rounds = server_->core().scheduler.rounds();
  std::this_thread::sleep_for(300ms);
  EXPECT_EQ(server_->core().scheduler.rounds(), idle_rounds) << "a cancelled reference kept rendering";
  EXPECT_TRUE(std::filesystem::is_empty(cache_dir_.path) || !std::filesystem::exists(cache_dir_.path))
      << "a cancelled reference was cached";

  // SIGTERM's drain ends a reference in progress with UNAVAILABLE.
  grpc::Status drained;
  std::thread t([&] {
    v1::Reference r;
    drained = reference(long_request(200), &r);
  });
  ASSERT_TRUE(wait_until([&] { return server_->core().scheduler.rounds() >= idle_rounds + 2; }, 60s));
  server_->drain();
  t.join();
  EXPECT_EQ(drained.error_code(), StatusCode::UNAVAILABLE) << drained.error_message();
  EXPECT_NE(drained.error_message().find("draining"), std::string::npos) << drained.error_message();
}

}  // namespace
}  // namespace strata::test
