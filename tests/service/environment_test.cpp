// A session's environment map (SceneSource.environment) and punctual lights moved by the client
// (FrameInput.light_transforms), over real gRPC: what the scene analysis and the decisions say,
// the memory group, and that the frames show them.
#include <cmath>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <optional>

#include "harness.h"

namespace strata::test {
namespace {

class EnvironmentTest : public ServiceTest {};

std::string file_text(const std::filesystem::path& p) {
  std::ifstream in(p, std::ios::binary);
  return std::string(std::istreambuf_iterator<char>(in), {});
}

double image_mean(const image::Image& img) {
  double sum = 0.0;
  for (size_t i = 0; i < img.rgba.size(); i += 4) sum += img.rgba[i] + img.rgba[i + 1] + img.rgba[i + 2];
  return sum / double(img.rgba.size() / 4);
}

// cornell's open front lets the sky in: the same session with a map sent inline and one from the
// scene directory (turned, brighter) differ, and each says what it rendered.
TEST_F(EnvironmentTest, AMapSentInlineOrByPathLightsTheScene) {
  const std::filesystem::path sky = std::filesystem::path(STRATA_TEST_DATA_DIR) / "environment" / "sky_8x4.hdr";
  std::filesystem::copy_file(sky, scene_dir_.path / "sky.hdr");
  auto plain = session_request("cornell", 24, 16);
  auto inline_map = plain;
  inline_map.mutable_scene()->mutable_environment()->set_image(file_text(sky));
  inline_map.mutable_scene()->mutable_environment()->set_label("sky_8x4.hdr");
  auto by_path = plain;
  by_path.mutable_scene()->mutable_environment()->set_path("sky.hdr");
  by_path.mutable_scene()->mutable_environment()->set_intensity(4.0f);
  by_path.mutable_scene()->mutable_environment()->set_rotation_degrees(90.0f);

  double means[3];
  const v1::CreateSessionRequest* requests[3] = {&plain, &inline_map, &by_path};
  for (int i = 0; i < 3; ++i) {
    const v1::Session s = create_ok(stub(), *requests[i]);
    if (i == 0) {
      EXPECT_TRUE(s.analysis().environment_map().empty());
      EXPECT_EQ(s.memory().bytes_by_group().count("environment"), 0u);
    } else {
      EXPECT_NE(s.analysis().environment_map().find("(8 x 4 texels)"), std::string::npos) << s.analysis().environment_map();
      EXPECT_TRUE(s.analysis().environment_light());
      EXPECT_GT(s.memory().bytes_by_group().at("environment"), 8u * 4u * 16u);
      const v1::Decision* nee = decision(s, "next_event_estimation");
      ASSERT_NE(nee, nullptr);
      EXPECT_NE(nee->reason().find("environment map"), std::string::npos) << nee->reason();
    }
    const auto frames = stream_frames(stub(), s.name(), 2);
    ASSERT_EQ(frames.size(), 2u);
    const image::Image img = frame_image(frames.back());
    for (float v : img.rgba) ASSERT_TRUE(std::isfinite(v));
    means[i] = image_mean(img);
    EXPECT_TRUE(delete_session(stub(), s.name()).ok());
  }
  EXPECT_GT(means[1], means[0] * 1.05) << "the inline sky adds light";
  EXPECT_GT(means[2], means[1] * 1.5) << "four times the sky adds more";
}

// light_sampler auto, the default, takes the light tree on night-street (64 punctual lights and
// hundreds of emissive triangles) and power on cornell (two emissive triangles), and says why; an
// explicit choice stays, with what auto would have taken.
TEST_F(EnvironmentTest, TheLightSamplerFollowsTheScenesBoundedLights) {
  auto sampler = [&](const std::string& scene, std::optional<v1::LightSampler> asked) {
    auto req = session_request(scene, 16, 16);
    if (asked) req.mutable_options()->set_light_sampler(*asked);
    const v1::Session s = create_ok(stub(), req);
    EXPECT_TRUE(delete_session(stub(), s.name()).ok());
    const v1::Decision* d = decision(s, "light_sampler");
    return d ? *d : v1::Decision{};
  };
  const v1::Decision street = sampler("night-street", std::nullopt);
  EXPECT_EQ(street.value(), "tree");
  EXPECT_EQ(street.requested(), "");
  EXPECT_NE(street.reason().find("auto: the scene has 822 bounded lights"), std::string::npos) << street.reason();
  const v1::Decision cornell = sampler("cornell", v1::LIGHT_SAMPLER_AUTO);
  EXPECT_EQ(cornell.value(), "power");
  EXPECT_EQ(cornell.requested(), "auto");
  EXPECT_NE(cornell.reason().find("auto: the scene has 2 bounded lights"), std::string::npos) << cornell.reason();
  const v1::Decision asked = sampler("night-street", v1::LIGHT_SAMPLER_POWER);
  EXPECT_EQ(asked.value(), "power");
  EXPECT_NE(asked.reason().find("as asked; auto would take tree"), std::string::npos) << asked.reason();
}

// cornell-lamps' lights moved by the client: the analysis lists them, and a light sent far away
// darkens the frame.
TEST_F(EnvironmentTest, TheClientMovesAPunctualLight) {
  const v1::Session s = create_ok(stub(), session_request("cornell-lamps", 24, 16));
  ASSERT_GE(s.analysis().lights_size(), 1);
  EXPECT_EQ(s.analysis().lights(0).id(), 0u);
  StreamClient stream(stub());
  v1::FrameInput first = frame_input(1, s.name(), 0);
  ASSERT_TRUE(stream.send(first));
  const auto before = stream.read();
  ASSERT_TRUE(before.has_value());
  v1::FrameInput moved = frame_input(2);
  for (int l = 0; l < s.analysis().lights_size(); ++l) {
    auto* t = moved.add_light_transforms();
    t->set_light_id(uint32_t(l));
    t->mutable_translation()->set_x(0.0f);
    t->mutable_translation()->set_y(1000.0f);
    t->mutable_translation()->set_z(0.0f);
    t->mutable_rotation()->set_w(0.70710678f);  // -Z turned to +Y: shining up, under the box's floor
    t->mutable_rotation()->set_x(0.70710678f);
  }
  ASSERT_TRUE(stream.send(moved));
  const auto after = stream.read();
  ASSERT_TRUE(after.has_value());
  EXPECT_TRUE(stream.close().ok());
  EXPECT_LT(image_mean(frame_image(*after)), 0.5 * image_mean(frame_image(*before)));
}

}  // namespace
}  // namespace strata::test
