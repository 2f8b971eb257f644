// The DOMAIN_MAP image encoding (restir-multilayer's coverage dashboard): a frame that asks for it
// carries an 8-bit RGB PNG whose pixels add up to the frame's own ML Table 1 statistics (active
// domains by layer, disoccluded pixels, covered ones), and a method without pixel layers refuses
// it with INVALID_ARGUMENT naming the field.
#include <cmath>
#include <span>

#include "harness.h"

namespace strata::test {
namespace {

using DomainMapTest = ServiceTest;

TEST_F(DomainMapTest, MapAddsUpToTheFramesDomainStatistics) {
  auto req = session_request("carousel", 32, 32, 1, 3, {v1::IMAGE_ENCODING_RAW_RGBA16F, v1::IMAGE_ENCODING_DOMAIN_MAP});
  req.clear_options();
  req.set_method("restir-multilayer");
  req.mutable_options()->set_layers(3);
  req.mutable_options()->set_hole_fill_radius(0);
  const v1::Session s = create_ok(stub(), req);
  const auto frames = stream_frames(stub(), s.name(), 4);
  ASSERT_EQ(frames.size(), 4u);
  uint64_t deep_seen = 0;
  for (const auto& f : frames) {
    SCOPED_TRACE("frame " + std::to_string(f.frame_index()));
    const v1::Image* map = find_image(f, v1::IMAGE_ENCODING_DOMAIN_MAP);
    ASSERT_NE(map, nullptr);
    ASSERT_EQ(map->width(), 32u);
    ASSERT_EQ(map->height(), 32u);
    const image::Image png = image::decode_png(std::span(reinterpret_cast<const uint8_t*>(map->data().data()), map->data().size()));
    ASSERT_EQ(png.width, 32u);
    uint64_t active = 0, disoccluded = 0, covered = 0;
    for (size_t i = 0; i < size_t(png.width) * png.height; ++i) {
      const long r = std::lround(png.rgba[4 * i + 0] * 255.0f), g = std::lround(png.rgba[4 * i + 1] * 255.0f),
                 b = std::lround(png.rgba[4 * i + 2] * 255.0f);
      ASSERT_EQ(r % 32, 0) << "R is 32 x the active domains (at most 3 here)";
      ASSERT_TRUE(g == 0 || g == 255);
      ASSERT_TRUE(b == 0 || (b == 255 && g == 255)) << "only a disoccluded pixel can be covered";
      active += uint64_t(r / 32);
      disoccluded += g == 255;
      covered += b == 255;
    }
    const auto& reuse = f.statistics().reuse();
    ASSERT_EQ(reuse.active_domains_by_layer_size(), 3);
    uint64_t by_layer = 0;
    for (uint64_t n : reuse.active_domains_by_layer()) by_layer += n;
    EXPECT_EQ(active, by_layer);
    EXPECT_EQ(disoccluded, reuse.disoccluded_pixels());
    EXPECT_EQ(covered, reuse.disoccluded_covered());
    deep_seen += reuse.deep_domains();
  }
  EXPECT_GT(deep_seen, 0u) << "carousel's moving objects hide surfaces that stay active";
}

// `layers auto`: the session's decision carries the count measured on the scene's first frame.
TEST_F(DomainMapTest, LayersAutoDecisionSaysTheMeasuredCount) {
  auto req = session_request("carousel", 32, 32);
  req.clear_options();
  req.set_method("restir-multilayer");
  const v1::Session s = create_ok(stub(), req);
  const v1::Decision* layers = nullptr;
  for (const auto& d : s.decisions())
    if (d.name() == "layers") layers = &d;
  ASSERT_NE(layers, nullptr);
  EXPECT_TRUE(layers->applies());
  EXPECT_EQ(layers->value(), "3") << layers->reason();  // carousel: docs/BENCHMARKS.md, "Multi-layer reservoir splatting"
  EXPECT_NE(layers->reason().find("measured on the scene's first frame"), std::string::npos) << layers->reason();
}

TEST_F(DomainMapTest, MethodsWithoutLayersRefuseIt) {
  auto req = session_request("cornell", 16, 16, 1, 0, {v1::IMAGE_ENCODING_RAW_RGBA16F, v1::IMAGE_ENCODING_DOMAIN_MAP});
  req.clear_options();
  req.set_method("restir-splat");
  v1::Session out;
  const grpc::Status st = create_session(stub(), req, &out);
  EXPECT_EQ(st.error_code(), grpc::StatusCode::INVALID_ARGUMENT);
  EXPECT_NE(st.error_message().find("encodings[1] = DOMAIN_MAP but method restir-splat"), std::string::npos) << st.error_message();
}

}  // namespace
}  // namespace strata::test
