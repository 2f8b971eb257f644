// Skinned and morphing instances driven by the client (FrameInput.joint_poses, morph_weights) over
// real gRPC: the scene analysis lists them with their joint and target counts, a joint pose sent by
// the client moves the flag's silhouette, and weights the blob's; bad poses are refused by field.
#include <cmath>
#include <functional>
#include <limits>

#include "harness.h"

namespace strata::test {
namespace {

class CharactersTest : public ServiceTest {};

// Mean absolute difference of two images over 4 x 4 pixel blocks (sum of RGB).
double difference(const image::Image& a, const image::Image& b) {
  double sum = 0.0;
  size_t blocks = 0;
  for (uint32_t by = 0; by + 4 <= a.height; by += 4) {
    for (uint32_t bx = 0; bx + 4 <= a.width; bx += 4) {
      double d = 0.0;
      for (uint32_t y = by; y < by + 4; ++y) {
        for (uint32_t x = bx; x < bx + 4; ++x) {
          const size_t i = 4 * (size_t(y) * a.width + x);
          d += double(a.rgba[i] + a.rgba[i + 1] + a.rgba[i + 2]) - double(b.rgba[i] + b.rgba[i + 1] + b.rgba[i + 2]);
        }
      }
      sum += std::abs(d / 16.0);
      ++blocks;
    }
  }
  return sum / double(blocks);
}

uint32_t instance_named(const v1::Session& s, const std::string& name) {
  for (const auto& i : s.analysis().instances())
    if (i.name() == name) return i.id();
  ADD_FAILURE() << "no instance " << name;
  return 0;
}

// Every joint past the first turned by `angle` about +Y, chained, from the flag's first joint at
// `origin` with joints `spacing` apart: joint to world of each joint.
v1::JointPose fold_flag(uint32_t id, uint32_t joints, float angle) {
  v1::JointPose pose;
  pose.set_instance_id(id);
  float heading = 0.0f, x = -0.55f, z = -0.25f;
  for (uint32_t k = 0; k < joints; ++k) {
    if (k > 0) {
      x += 0.25f * std::cos(heading);
      z -= 0.25f * std::sin(heading);
      heading += angle;
    }
    auto* j = pose.add_joints();
    j->set_joint(k);
    j->mutable_translation()->set_x(x);
    j->mutable_translation()->set_y(1.35f);
    j->mutable_translation()->set_z(z);
    j->mutable_rotation()->set_w(std::cos(0.5f * heading));
    j->mutable_rotation()->set_y(std::sin(0.5f * heading));
  }
  return pose;
}

// One frame of a new session (the same seed every time, so the same random numbers) from the default
// animation's frame 0 with `edit` applied to its input.
image::Image one_frame(v1::RenderService::Stub& stub, const std::function<void(const v1::Session&, v1::FrameInput&)>& edit,
                       v1::Session* session = nullptr) {
  const v1::Session s = create_ok(stub, session_request("characters", 32, 32, 16, 7));
  if (session) *session = s;
  StreamClient stream(stub);
  v1::FrameInput in = frame_input(1, s.name(), 0);
  edit(s, in);
  image::Image out;
  EXPECT_TRUE(stream.send(in));
  const auto frame = stream.read();
  EXPECT_TRUE(frame.has_value());
  if (frame) {
    out = frame_image(*frame);
    bool deform_pass = false;
    for (const auto& p : frame->pass_ms()) deform_pass = deform_pass || p.pass() == "deform";
    EXPECT_TRUE(deform_pass) << "the frame's pass times list the deformation";
  }
  EXPECT_TRUE(stream.close().ok());
  EXPECT_TRUE(delete_session(stub, s.name()).ok());
  return out;
}

TEST_F(CharactersTest, TheClientPosesTheFlagAndWeightsTheBlob) {
  v1::Session s;
  const image::Image flat = one_frame(stub(), [](const v1::Session& session, v1::FrameInput& in) {
    *in.add_joint_poses() = fold_flag(instance_named(session, "flag"), 5, 0.0f);
  }, &s);
  const uint32_t flag = instance_named(s, "flag");
  const uint32_t blob = instance_named(s, "blob");
  EXPECT_EQ(s.analysis().instances(int(flag)).joints(), 5u);
  EXPECT_EQ(s.analysis().instances(int(flag)).morph_targets(), 0u);
  EXPECT_EQ(s.analysis().instances(int(blob)).joints(), 0u);
  EXPECT_EQ(s.analysis().instances(int(blob)).morph_targets(), 2u);
  EXPECT_GT(s.memory().bytes_by_group().at("deformation"), 0u);
  const image::Image again = one_frame(stub(), [&](const v1::Session&, v1::FrameInput& in) { *in.add_joint_poses() = fold_flag(flag, 5, 0.0f); });
  const image::Image folded = one_frame(stub(), [&](const v1::Session&, v1::FrameInput& in) { *in.add_joint_poses() = fold_flag(flag, 5, 0.6f); });
  const image::Image weighted = one_frame(stub(), [&](const v1::Session&, v1::FrameInput& in) {
    *in.add_joint_poses() = fold_flag(flag, 5, 0.0f);
    auto* w = in.add_morph_weights();
    w->set_instance_id(blob);
    w->add_weights(1.0f);  // breathe: 30% larger
    w->add_weights(1.0f);  // and squashed
  });
  // The same seed, frame and state render the same image; a pose or weights that reached the
  // device change it where the flag or the blob moved (the flag covers about a tenth of the image).
  EXPECT_EQ(difference(flat, again), 0.0) << "the same state rendered differently";
  EXPECT_GT(difference(flat, folded), 0.01) << "folding the flag";
  EXPECT_GT(difference(flat, weighted), 0.002) << "growing the blob";
}

TEST_F(CharactersTest, BadPosesAndWeightsAreRefusedByField) {
  const v1::Session s = create_ok(stub(), session_request("characters", 16, 16));
  const uint32_t flag = instance_named(s, "flag");
  const uint32_t blob = instance_named(s, "blob");
  struct Case {
    std::function<void(v1::FrameInput&)> edit;
    std::string message;
  };
  const std::vector<Case> cases = {
      {[&](auto& in) { *in.add_joint_poses() = fold_flag(blob, 1, 0.0f); },
       "joint_poses[0].instance_id = " + std::to_string(blob) + " 'blob' is not skinned"},
      {[&](auto& in) { *in.add_joint_poses() = fold_flag(flag, 6, 0.0f); },
       "joint_poses[0].joints[5].joint = 5 is not a joint of instance " + std::to_string(flag) + " 'flag': its skin has 5 joints"},
      {[&](auto& in) {
         auto pose = fold_flag(flag, 1, 0.0f);
         pose.mutable_joints(0)->mutable_translation()->set_x(std::nanf(""));
         *in.add_joint_poses() = pose;
       },
       "joint_poses[0].joints[0].translation.x"},
      {[&](auto& in) {
         auto pose = fold_flag(flag, 1, 0.0f);
         pose.mutable_joints(0)->clear_rotation();
         *in.add_joint_poses() = pose;
       },
       "joint_poses[0].joints[0].rotation is required"},
      {[&](auto& in) {
         auto* w = in.add_morph_weights();
         w->set_instance_id(blob);
         w->add_weights(0.5f);
       },
       "morph_weights[0].weights has 1 weights; instance " + std::to_string(blob) + " 'blob' has 2 morph target(s)"},
      {[&](auto& in) {
         auto* w = in.add_morph_weights();
         w->set_instance_id(blob);
         w->add_weights(std::numeric_limits<float>::infinity());
         w->add_weights(0.0f);
       },
       "morph_weights[0].weights[0] = inf is outside [-16, 16]"},
  };
  for (const Case& c : cases) {
    SCOPED_TRACE(c.message);
    StreamClient stream(stub());
    v1::FrameInput in = frame_input(1, s.name(), 0);
    c.edit(in);
    stream.send(in);
    EXPECT_FALSE(stream.read()) << "a bad input was rendered";
    const grpc::Status status = stream.finish();
    EXPECT_EQ(status.error_code(), grpc::StatusCode::INVALID_ARGUMENT) << status.error_message();
    EXPECT_NE(status.error_message().find(c.message), std::string::npos) << status.error_message();
    ASSERT_TRUE(wait_until([&] {
      v1::Session v;
      return get_session(stub(), s.name(), &v).ok() && v.state() == v1::Session::IDLE;
    }, std::chrono::seconds(10)));
  }
  // The session renders after every refusal.
  EXPECT_EQ(stream_frames(stub(), s.name(), 1).size(), 1u);
}

}  // namespace
}  // namespace strata::test
