// Streaming frames: statistics with every frame, the three encodings agreeing, inputs that change
// the picture, resolution changes that reset history and say so, latest-input-wins accounting,
// and a clean end when the client half-closes.
#include <cmath>

#include "harness.h"
#include "scene/scene_io.h"

namespace strata::test {
namespace {

using StreamingTest = ServiceTest;

bool same_pixels(const image::Image& a, const image::Image& b) { return a.width == b.width && a.height == b.height && a.rgba == b.rgba; }

TEST_F(StreamingTest, StreamsFramesWithStatisticsInEveryEncoding) {
  auto req = session_request("cornell", 32, 24, 2, 1,
                             {v1::IMAGE_ENCODING_RAW_RGBA16F, v1::IMAGE_ENCODING_EXR_HALF, v1::IMAGE_ENCODING_PNG_PREVIEW});
  const v1::Session s = create_ok(stub(), req);
  const auto frames = stream_frames(stub(), s.name(), 4);
  ASSERT_EQ(frames.size(), 4u);
  for (size_t i = 0; i < frames.size(); ++i) {
    const v1::Frame& f = frames[i];
    SCOPED_TRACE("frame " + std::to_string(i));
    EXPECT_EQ(f.frame_index(), i);
    EXPECT_EQ(f.input_sequence(), i + 1);
    EXPECT_EQ(f.frames_dropped(), 0u);
    EXPECT_EQ(f.history_reset(), i == 0);
    if (i == 0) {
      EXPECT_EQ(f.history_reset_reason(), "first frame of the session");
    }
    ASSERT_EQ(f.images_size(), 3);
    EXPECT_EQ(f.images(0).encoding(), v1::IMAGE_ENCODING_RAW_RGBA16F);
    EXPECT_EQ(f.images(0).data().size(), 32u * 24u * 8u);
    const image::Image raw = frame_image(f, v1::IMAGE_ENCODING_RAW_RGBA16F);
    const image::Image exr = frame_image(f, v1::IMAGE_ENCODING_EXR_HALF);
    EXPECT_TRUE(same_pixels(raw, exr)) << "RAW_RGBA16F and EXR_HALF disagree";
    const auto& png = find_image(f, v1::IMAGE_ENCODING_PNG_PREVIEW)->data();
    std::vector<uint8_t> png_bytes(png.begin(), png.end());
    const image::Image preview = image::decode_png(png_bytes);
    EXPECT_EQ(preview.width, 32u);
    double sum = 0.0;
    for (float v : raw.rgba) {
      ASSERT_TRUE(std::isfinite(v));
      sum += v;
    }
    EXPECT_GT(sum, 0.0) << "black frame";

    const auto& st = f.statistics();
    EXPECT_GT(st.rays_total(), 32u * 24u * 2u);
    EXPECT_EQ(st.paths(), 32u * 24u * 2u);
    EXPECT_TRUE(st.rays_traced().contains("shadow"));
    EXPECT_FALSE(st.has_reuse()) << "pt reports no reuse statistics";
    bool path_trace_ran = false, temporal_left_out = false;
    for (const auto& p : st.passes()) {
      if (p.pass() == "path_trace") path_trace_ran = p.ran();
      if (p.pass() == "temporal") temporal_left_out = !p.ran() && !p.reason().empty();
    }
    EXPECT_TRUE(path_trace_ran);
    EXPECT_TRUE(temporal_left_out);
    ASSERT_GE(f.pass_ms_size(), 2);
    EXPECT_GT(f.gpu_ms_total(), 0.0);
    EXPECT_GT(f.timing().render_ms(), 0.0);
    EXPECT_GT(f.timing().encode_ms(), 0.0);
    EXPECT_EQ(f.resolution().width(), 32u);
  }
  // Frames of an animation with different random streams differ.
  EXPECT_FALSE(same_pixels(frame_image(frames[0]), frame_image(frames[1])));
  v1::Session after;
  ASSERT_TRUE(get_session(stub(), s.name(), &after).ok());
  EXPECT_EQ(after.frames_rendered(), 4u);
  EXPECT_EQ(after.last_input_sequence(), 4u);
  EXPECT_GT(after.passes_size(), 0);
}

TEST_F(StreamingTest, CameraTransformAndLodInputsChangeThePicture) {
  const scene::Scene lc = scene::builtin_scene("lod-cliff");
  uint32_t lod_instance = 0;
  for (uint32_t i = 0; i < lc.instances.size(); ++i)
    if (lc.instances[i].lod_meshes.size() > 1) lod_instance = i;
  ASSERT_GT(lc.instances[lod_instance].lod_meshes.size(), 1u);

  const v1::Session s = create_ok(stub(), session_request("lod-cliff", 32, 24, 1, 3));
  StreamClient c(stub());
  ASSERT_TRUE(c.send(frame_input(1, s.name(), 0)));
  auto base = c.read();
  ASSERT_TRUE(base);

  v1::FrameInput moved = frame_input(2);  // same state, camera turned and moved
  auto* cam = moved.mutable_camera();
  cam->mutable_position()->set_x(lc.camera.position.x + 0.5f);
  cam->mutable_position()->set_y(lc.camera.position.y);
  cam->mutable_position()->set_z(lc.camera.position.z);
  cam->mutable_orientation()->set_w(lc.camera.orientation.w);
  cam->mutable_orientation()->set_x(lc.camera.orientation.x);
  cam->mutable_orientation()->set_y(lc.camera.orientation.y);
  cam->mutable_orientation()->set_z(lc.camera.orientation.z);
  cam->set_vertical_fov(lc.camera.yfov * 0.8f);
  ASSERT_TRUE(c.send(moved));
  auto f2 = c.read();
  ASSERT_TRUE(f2);
  EXPECT_EQ(f2->input_sequence(), 2u);
  EXPECT_FALSE(same_pixels(frame_image(*base), frame_image(*f2)));

  v1::FrameInput lod = frame_input(3);
  auto* change = lod.add_lod_changes();
  change->set_instance_id(lod_instance);
  change->set_level(uint32_t(lc.instances[lod_instance].lod_meshes.size() - 1));
  auto* t = lod.add_transforms();
  t->set_instance_id(lod_instance);
  t->mutable_translation()->set_y(0.25f);
  t->mutable_rotation()->set_w(1.0f);
  t->mutable_scale()->set_x(1.0f);
  t->mutable_scale()->set_y(1.0f);
  t->mutable_scale()->set_z(1.0f);
  ASSERT_TRUE(c.send(lod));
  auto f3 = c.read();
  ASSERT_TRUE(f3);
  EXPECT_EQ(f3->input_sequence(), 3u);
  EXPECT_FALSE(f3->history_reset());
  EXPECT_GE(f3->statistics().tlas_builds() + f3->statistics().tlas_refits(), 1u);
  EXPECT_TRUE(c.close().ok());
}

TEST_F(StreamingTest, ResolutionChangeResetsHistoryAndSaysSo) {
  const v1::Session s = create_ok(stub(), session_request("cornell", 32, 24));
  StreamClient c(stub());
  ASSERT_TRUE(c.send(frame_input(1, s.name(), 0)));
  ASSERT_TRUE(c.read());
  v1::FrameInput in = frame_input(2, "", 1);
  in.mutable_resolution()->set_width(40);
  in.mutable_resolution()->set_height(30);
  ASSERT_TRUE(c.send(in));
  auto f = c.read();
  ASSERT_TRUE(f);
  EXPECT_TRUE(f->history_reset());
  EXPECT_NE(f->history_reset_reason().find("resolution changed from 32x24 to 40x30"), std::string::npos)
      << f->history_reset_reason();
  EXPECT_EQ(f->images(0).width(), 40u);
  EXPECT_EQ(f->images(0).data().size(), 40u * 30u * 8u);
  EXPECT_EQ(f->statistics().memory_bytes().at("image"), 40u * 30u * 16u);
  ASSERT_TRUE(c.send(frame_input(3, "", 2)));
  auto g = c.read();
  ASSERT_TRUE(g);
  EXPECT_FALSE(g->history_reset());
  EXPECT_TRUE(c.close().ok());
  v1::Session after;
  ASSERT_TRUE(get_session(stub(), s.name(), &after).ok());
  EXPECT_EQ(after.resolution().width(), 40u);
}

TEST_F(StreamingTest, InputsSentAheadAreMergedAndCounted) {
  const v1::Session s = create_ok(stub(), session_request("cornell", 48, 36, 4));
  StreamClient c(stub());
  constexpr uint64_t inputs = 12;
  for (uint64_t i = 1; i <= inputs; ++i) ASSERT_TRUE(c.send(frame_input(i, i == 1 ? s.name() : "", uint32_t(i - 1))));
  uint64_t received = 0, dropped = 0, coalesced = 0, last = 0;
  while (last < inputs) {
    auto f = c.read();
    ASSERT_TRUE(f) << "stream ended before the last input's frame";
    EXPECT_GT(f->input_sequence(), last);
    last = f->input_sequence();
    ++received;
    dropped += f->frames_dropped();
    coalesced += f->inputs_coalesced();
  }
  EXPECT_TRUE(c.close().ok());
  // Every input was either rendered or merged into a later one; every rendered frame was either
  // sent or dropped.
  v1::Session after;
  ASSERT_TRUE(get_session(stub(), s.name(), &after).ok());
  EXPECT_EQ(after.frames_rendered() + after.inputs_coalesced(), inputs);
  EXPECT_EQ(received + dropped, after.frames_rendered());
  EXPECT_EQ(coalesced, after.inputs_coalesced());
}

TEST_F(StreamingTest, HalfCloseEndsTheStreamAfterTheLastFrame) {
  const v1::Session s = create_ok(stub(), session_request("cornell", 24, 16));
  StreamClient c(stub());
  for (uint64_t i = 1; i <= 3; ++i) ASSERT_TRUE(c.send(frame_input(i, i == 1 ? s.name() : "", uint32_t(i - 1))));
  // Half-close at once: the server still renders and sends the pending input, then ends with OK.
  std::vector<v1::Frame> frames;
  const grpc::Status st = c.close(&frames);
  EXPECT_TRUE(st.ok()) << st.error_message();
  ASSERT_FALSE(frames.empty());
  EXPECT_EQ(frames.back().input_sequence(), 3u);
}

}  // namespace
}  // namespace strata::test
