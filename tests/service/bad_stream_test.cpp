// Bad FrameInputs: each ends its stream with the right status and a message naming the field and
// the limit; the session itself survives (a new stream works) and another session keeps streaming.
#include <limits>

#include "harness.h"

namespace strata::test {
namespace {

using grpc::StatusCode;

struct StreamCase {
  std::string what;
  bool first;          // the bad input is the stream's first message (no valid prefix)
  v1::FrameInput bad;
  StatusCode code;
  std::string message;
};

v1::InstanceTransform identity(uint32_t id) {
  v1::InstanceTransform t;
  t.set_instance_id(id);
  t.mutable_translation();
  t.mutable_rotation()->set_w(1.0f);
  t.mutable_scale()->set_x(1.0f);
  t.mutable_scale()->set_y(1.0f);
  t.mutable_scale()->set_z(1.0f);
  return t;
}

v1::Camera good_camera() {
  v1::Camera c;
  c.mutable_position()->set_z(3.0f);
  c.mutable_orientation()->set_w(1.0f);
  c.set_vertical_fov(0.8f);
  return c;
}

class BadStreamTest : public ServiceTest {};

TEST_F(BadStreamTest, EveryBadInputEndsItsStreamWithStatusAndMessage) {
  const v1::Session other = create_ok(stub(), session_request("carousel", 24, 16));
  BackgroundStream background(address(), other.name());
  const v1::Session victim = create_ok(stub(), session_request("cornell", 32, 24));
  ASSERT_TRUE(wait_until([&] { return background.frames() >= 2; }, 30s));

  const float nan = std::numeric_limits<float>::quiet_NaN();
  const auto invalid = StatusCode::INVALID_ARGUMENT;
  std::vector<StreamCase> cases;
  auto add = [&](std::string what, bool first, auto edit, StatusCode code, std::string message) {
    v1::FrameInput in = frame_input(first ? 1 : 2, first ? victim.name() : "", 0);
    edit(in);
    cases.push_back({std::move(what), first, std::move(in), code, std::move(message)});
  };
  add("no session in the first input", true, [](auto& in) { in.clear_session(); }, invalid,
      "session is required in the first FrameInput");
  add("malformed session", true, [](auto& in) { in.set_session("victim"); }, invalid, "session = 'victim' is not a session name");
  add("unknown session", true, [](auto& in) { in.set_session("sessions/ffffffffffffffff"); }, StatusCode::NOT_FOUND,
      "session 'sessions/ffffffffffffffff' does not exist");
  add("sequence 0", true, [](auto& in) { in.set_sequence(0); }, invalid, "sequence = 0");
  add("sequence not increasing", false, [](auto& in) { in.set_sequence(1); }, invalid,
      "sequence = 1 is not greater than the previous sequence 1");
  add("another session later", false, [](auto& in) { in.set_session("sessions/abc"); }, invalid,
      "differs from this stream's session");
  add("NaN in the camera position", false, [&](auto& in) {
    *in.mutable_camera() = good_camera();
    in.mutable_camera()->mutable_position()->set_y(nan);
  }, invalid, "camera.position.y = nan is not finite");
  add("camera too far away", false, [&](auto& in) {
    *in.mutable_camera() = good_camera();
    in.mutable_camera()->mutable_position()->set_x(1e9f);
  }, invalid, "camera.position.x = 1e+09 is outside [-1e+08, 1e+08]");
  add("zero quaternion", false, [&](auto& in) {
    *in.mutable_camera() = good_camera();
    in.mutable_camera()->mutable_orientation()->set_w(0.0f);
  }, invalid, "camera.orientation has norm 0");
  add("camera without orientation", false, [&](auto& in) {
    *in.mutable_camera() = good_camera();
    in.mutable_camera()->clear_orientation();
  }, invalid, "camera.orientation is required");
  add("zero field of view", false, [&](auto& in) {
    *in.mutable_camera() = good_camera();
    in.mutable_camera()->set_vertical_fov(0.0f);
  }, invalid, "camera.vertical_fov = 0 rad is outside (0, pi)");
  add("negative aperture", false, [&](auto& in) {
    *in.mutable_camera() = good_camera();
    in.mutable_camera()->set_aperture(-0.5f);
  }, invalid, "camera.aperture = -0.5 m is outside [0, 1000]");
  add("aperture without focus", false, [&](auto& in) {
    *in.mutable_camera() = good_camera();
    in.mutable_camera()->set_aperture(0.1f);
  }, invalid, "camera.focus_distance = 0 must be > 0 when camera.aperture > 0");
  add("shutter over 1", false, [&](auto& in) {
    *in.mutable_camera() = good_camera();
    in.mutable_camera()->set_shutter(2.0f);
  }, invalid, "camera.shutter = 2 is outside [0, 1]");
  add("unknown instance id", false, [](auto& in) { *in.add_transforms() = identity(99); }, invalid,
      "transforms[0].instance_id = 99 is not an instance id: scene 'cornell' has 4 instances (ids 0..3)");
  add("unknown light id", false, [](auto& in) {
    auto* l = in.add_light_transforms();
    l->set_light_id(0);
    *l->mutable_translation() = identity(0).translation();
    *l->mutable_rotation() = identity(0).rotation();
  }, invalid, "light_transforms[0].light_id = 0 is not a light id: scene 'cornell' has 0 punctual light(s)");
  add("same instance twice", false, [](auto& in) {
    *in.add_transforms() = identity(1);
    *in.add_transforms() = identity(1);
  }, invalid, "transforms[1].instance_id = 1 appears more than once");
  add("degenerate scale", false, [](auto& in) {
    auto t = identity(0);
    t.mutable_scale()->set_y(0.0f);
    *in.add_transforms() = t;
  }, invalid, "transforms[0].scale.y = 0 is smaller in magnitude than 1e-06");
  add("transform without rotation", false, [](auto& in) {
    auto t = identity(2);
    t.clear_rotation();
    *in.add_transforms() = t;
  }, invalid, "transforms[0].rotation is required");
  add("LoD level out of range", false, [](auto& in) {
    auto* c = in.add_lod_changes();
    c->set_instance_id(0);
    c->set_level(3);
  }, invalid, "lod_changes[0].level = 3 is out of range for instance 0");
  add("LoD change of an unknown instance", false, [](auto& in) {
    auto* c = in.add_lod_changes();
    c->set_instance_id(4);
  }, invalid, "lod_changes[0].instance_id = 4 is not an instance id");
  add("zero resolution", false, [](auto& in) { in.mutable_resolution()->set_height(0); }, invalid,
      "resolution.width = 0 is outside [1, 1024]");
  add("oversize resolution", false, [](auto& in) {
    in.mutable_resolution()->set_width(1000);
    in.mutable_resolution()->set_height(1000);
  }, invalid, "resolution.width * resolution.height = 1000000 exceeds max_pixels = 307200");
  add("spp 0 in an option change", false, [](auto& in) { in.mutable_options()->set_spp(0); }, invalid,
      "options.spp = 0 is outside [1, 64] (limit max_spp)");
  add("unknown LoD mapping", false, [](auto& in) { in.mutable_options()->set_lod_mapping(static_cast<v1::LodMapping>(12)); },
      invalid, "options.lod_mapping = 12 is not one of");
  add("unspecified encoding", false, [](auto& in) { in.add_encodings(v1::IMAGE_ENCODING_UNSPECIFIED); }, invalid,
      "encodings[0] = 0 is not an image encoding");
  ASSERT_GE(cases.size(), 20u);

  const uint64_t before = background.frames();
  for (const auto& c : cases) {
    SCOPED_TRACE(c.what);
    StreamClient s(stub(), 30s);
    if (!c.first) {
      ASSERT_TRUE(s.send(frame_input(1, victim.name(), 0)));
      auto ok = s.read();
      ASSERT_TRUE(ok) << "the valid first input got no frame";
    }
    s.send(c.bad);
    EXPECT_FALSE(s.read()) << "a bad input was rendered";
    const grpc::Status st = s.finish();
    EXPECT_EQ(st.error_code(), c.code) << st.error_message();
    EXPECT_NE(st.error_message().find(c.message), std::string::npos)
        << "message '" << st.error_message() << "' does not contain '" << c.message << "'";
    // The session is free for the next stream once this one is gone.
    ASSERT_TRUE(wait_until([&] {
      v1::Session v;
      return get_session(stub(), victim.name(), &v).ok() && v.state() == v1::Session::IDLE;
    }, 10s));
  }

  // The victim session survived every bad stream, and the other session never noticed.
  const auto frames = stream_frames(stub(), victim.name(), 2);
  EXPECT_EQ(frames.size(), 2u);
  EXPECT_GT(background.frames(), before);
  const grpc::Status bg = background.stop();
  EXPECT_TRUE(bg.ok()) << bg.error_message();
}

}  // namespace
}  // namespace strata::test
