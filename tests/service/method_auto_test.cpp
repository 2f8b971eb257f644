// `method auto` (service/method_auto.h; docs/ARCHITECTURE.md, "Method auto"): the estimates it
// chooses by, and over real gRPC that it keeps pt where pt wins at equal time (foliage) and
// restir-gather where restir-gather wins (carousel-bounce, whose light is one bounce away), says
// so with its figures, keeps the chosen run's history, and calibrates again when the resolution
// changes. Images are small (lavapipe).
#include <cmath>
#include <random>

#include "harness.h"
#include "service/method_auto.h"

namespace strata::test {
namespace {

using MethodAutoTest = ServiceTest;

image::Image constant_image(uint32_t w, uint32_t h, float v) {
  return image::Image{w, h, std::vector<float>(size_t(4) * w * h, v)};
}

// Two runs of an estimator with per-pixel noise of standard deviation `sigma` around 1: the
// paired estimate is the RelMSE sigma^2 / (1 + 0.01), within sampling error.
TEST(MethodAutoEstimate, PairedRelMseEstimatesTheVarianceOfOneRun) {
  std::mt19937 rng(7);
  for (float sigma : {0.05f, 0.3f, 1.0f}) {
    std::normal_distribution<float> noise(1.0f, sigma);
    image::Image a = constant_image(128, 128, 1.0f), b = a;
    for (size_t i = 0; i < a.rgba.size(); ++i) {
      a.rgba[i] = noise(rng);
      b.rgba[i] = noise(rng);
    }
    const double expected = double(sigma) * sigma / 1.01;
    EXPECT_NEAR(service::paired_relmse(a, b, constant_image(128, 128, 1.0f)), expected, 0.03 * expected) << sigma;
  }
}

// One run's firefly does not move the reference estimate: the 3x3 median of the runs' mean.
TEST(MethodAutoEstimate, RobustReferenceIgnoresAFirefly) {
  image::Image a = constant_image(8, 8, 0.5f), b = a;
  a.pixel(3, 3)[0] = 1000.0f;
  const std::array<const image::Image*, 2> runs = {&a, &b};
  const image::Image ref = service::robust_reference(runs);
  EXPECT_FLOAT_EQ(ref.pixel(3, 3)[0], 0.5f);
  EXPECT_FLOAT_EQ(ref.pixel(0, 0)[1], 0.5f);
  // So the firefly counts in full: (1000 - 0.5)^2 / 2 / (0.25 + 0.01), over 8 x 8 x 3 terms.
  const double expected = 0.5 * 999.5 * 999.5 / 0.26 / (8 * 8 * 3);
  EXPECT_NEAR(service::paired_relmse(a, b, ref), expected, 1e-6 * expected);
}

// The lower RelMSE x ms wins; the cap follows pt's error per sample unless one was asked for.
TEST(MethodAutoEstimate, ChoosesTheLowerErrorAtEqualTimeAndTheCapFromPtsError) {
  EXPECT_STREQ(service::auto_method({0.2, 60.0}, {0.025, 150.0}).name, "restir-gather");  // cornell-like: 0.31
  EXPECT_STREQ(service::auto_method({0.06, 210.0}, {0.07, 620.0}).name, "pt");            // foliage-like: 3.4
  EXPECT_STREQ(service::auto_method({0.06, 100.0}, {NAN, 100.0}).name, "pt");
  EXPECT_FLOAT_EQ(service::auto_confidence_cap(5.7, std::nullopt), service::k_auto_hard_light_cap);
  EXPECT_FLOAT_EQ(service::auto_confidence_cap(0.2, std::nullopt), 2.0f);
  EXPECT_FLOAT_EQ(service::auto_confidence_cap(5.7, 3.0f), 3.0f);
}

// One measured frame decides only outside [1/2, 2], two outside [2/3, 3/2]; the last always does.
TEST(MethodAutoEstimate, DecidesEarlyOnlyWhereTheEstimateIsFarFromATie) {
  const service::CandidateEstimate pt{0.2, 100.0};
  auto reuse = [](double ratio) { return service::CandidateEstimate{0.2 * ratio, 100.0}; };
  EXPECT_FALSE(service::auto_decisive(pt, reuse(0.3), 0));
  EXPECT_TRUE(service::auto_decisive(pt, reuse(0.3), 1));
  EXPECT_TRUE(service::auto_decisive(pt, reuse(2.5), 1));
  EXPECT_FALSE(service::auto_decisive(pt, reuse(0.6), 1));
  EXPECT_FALSE(service::auto_decisive(pt, reuse(1.9), 1));
  EXPECT_TRUE(service::auto_decisive(pt, reuse(0.6), 2));
  EXPECT_TRUE(service::auto_decisive(pt, reuse(1.6), 2));
  EXPECT_FALSE(service::auto_decisive(pt, reuse(0.8), 2));
  EXPECT_FALSE(service::auto_decisive(pt, service::CandidateEstimate{NAN, 100.0}, 2));
  EXPECT_TRUE(service::auto_decisive(pt, reuse(1.0), 3));
  EXPECT_TRUE(service::auto_decisive(pt, service::CandidateEstimate{NAN, 100.0}, 3));
}

v1::CreateSessionRequest auto_request(const std::string& scene, const std::string& method, uint32_t size) {
  auto r = session_request(scene, size, size);
  r.clear_options();
  r.set_method(method);
  return r;
}

// Parses "est. RelMSE x ms of restir-gather R of pt's" from the method decision.
double ratio_of(const std::string& reason) {
  const std::string key = "est. RelMSE x ms of restir-gather ";
  const auto at = reason.find(key);
  return at == std::string::npos ? -1.0 : std::stod(reason.substr(at + key.size()));
}

struct AutoRun {
  v1::Session before, after;
  std::vector<v1::Frame> frames;
};

AutoRun run_auto(v1::RenderService::Stub& stub, const std::string& scene, const std::string& method, uint32_t size) {
  AutoRun r;
  r.before = create_ok(stub, auto_request(scene, method, size));
  r.frames = stream_frames(stub, r.before.name(), service::k_auto_calibration_frames + 2);
  EXPECT_TRUE(get_session(stub, r.before.name(), &r.after).ok());
  return r;
}

// The estimates' tolerance: at 64 x 64 over frames 2..4 the ratio of RelMSE x ms moved between
// 2.1 and 3.9 on foliage and between 0.13 and 0.64 on cornell over seeds 0..3 on a loaded 2-core VM
// (docs/ARCHITECTURE.md, "Method auto"; at 256x256 restir-gather / pt at equal time is 2.1-3.5 on
// foliage and 0.18-0.36 on cornell: docs/BENCHMARKS.md), so each must land on its side of 1.
// (carousel-bounce, 0.24 at 256x256, is near a tie at 64x64: 0.6-1.4.)
TEST_F(MethodAutoTest, AutoKeepsPtOnFoliageAndRestirGatherOnCornell) {
  const AutoRun foliage = run_auto(stub(), "foliage", "", 64);  // no method named: auto
  const AutoRun cornell = run_auto(stub(), "cornell", "auto", 64);

  for (const AutoRun* r : {&foliage, &cornell}) {
    const v1::Decision* calibrating = decision(r->before, "method");
    ASSERT_NE(calibrating, nullptr);
    EXPECT_NE(calibrating->reason().find("auto: calibrating from frame 0 for 3 to 5 frames"), std::string::npos)
        << calibrating->reason();
    ASSERT_EQ(r->frames.size(), service::k_auto_calibration_frames + 2);
    // The calibration's frames carry the other runs' GPU time, and the frame that ends it (on the
    // first measured frame where the estimate decides, at the latest the calibration's last) says
    // what was chosen.
    bool calibration_pass = false;
    for (const auto& p : r->frames[1].pass_ms()) calibration_pass |= p.pass() == "auto_calibration" && p.ms() > 0.0;
    EXPECT_TRUE(calibration_pass);
    size_t chosen_at = 0;
    while (chosen_at < r->frames.size() && r->frames[chosen_at].option_changes_size() == 0) ++chosen_at;
    ASSERT_GE(chosen_at, service::k_auto_first_measured);
    ASSERT_LT(chosen_at, service::k_auto_calibration_frames);
    ASSERT_EQ(r->frames[chosen_at].option_changes_size(), 1);
    EXPECT_EQ(r->frames[chosen_at].option_changes(0).name(), "method");
    EXPECT_EQ(r->frames[chosen_at].option_changes(0).value(), r->after.method());
    for (size_t f = chosen_at + 1; f < r->frames.size(); ++f) EXPECT_EQ(r->frames[f].option_changes_size(), 0) << f;
    for (size_t f = 1; f < r->frames.size(); ++f)
      EXPECT_FALSE(r->frames[f].history_reset()) << f << ": " << r->frames[f].history_reset_reason();
  }

  EXPECT_EQ(foliage.after.method(), "pt");
  const v1::Decision* fm = decision(foliage.after, "method");
  ASSERT_NE(fm, nullptr);
  EXPECT_EQ(fm->requested(), "");
  EXPECT_EQ(fm->value(), "pt");
  EXPECT_GT(ratio_of(fm->reason()), 1.0) << fm->reason();
  EXPECT_FALSE(foliage.frames.back().statistics().has_reuse()) << "pt renders after the choice";

  EXPECT_EQ(cornell.after.method(), "restir-gather");
  const v1::Decision* cm = decision(cornell.after, "method");
  ASSERT_NE(cm, nullptr);
  EXPECT_EQ(cm->requested(), "auto");
  EXPECT_LT(ratio_of(cm->reason()), 1.0) << cm->reason();
  EXPECT_TRUE(cornell.frames.back().statistics().has_reuse());
  // Its history goes on: the temporal pass took previous samples on the frames after the choice.
  EXPECT_GT(cornell.frames.back().statistics().reuse().counters().at("temporal.selected"), 0u);
}

// Where pt's error per sample shows the light is hard to find (carousel-bounce: a wall washer lights
// the ring one bounce away), auto runs restir-gather with the higher cap under motion (chosen on the
// calibration's first frame, before restir-gather's runs start), and says why; a cap the session
// asked for stays.
TEST_F(MethodAutoTest, AutoRaisesTheConfidenceCapWhereTheLightIsHardToFind) {
  const v1::Session s = create_ok(stub(), auto_request("carousel-bounce", "auto", 32));
  ASSERT_EQ(stream_frames(stub(), s.name(), 2).size(), 2u);
  v1::Session now;
  ASSERT_TRUE(get_session(stub(), s.name(), &now).ok());
  EXPECT_FLOAT_EQ(now.options().confidence_cap(), service::k_auto_hard_light_cap);
  const v1::Decision* cap = decision(now, "confidence_cap");
  ASSERT_NE(cap, nullptr);
  EXPECT_EQ(cap->value(), "4");
  EXPECT_NE(cap->reason().find("the light is hard to find"), std::string::npos) << cap->reason();

  auto asked = auto_request("carousel-bounce", "auto", 32);
  asked.mutable_options()->set_confidence_cap(3.0f);
  const v1::Session a = create_ok(stub(), asked);
  ASSERT_EQ(stream_frames(stub(), a.name(), 2).size(), 2u);
  ASSERT_TRUE(get_session(stub(), a.name(), &now).ok());
  EXPECT_FLOAT_EQ(now.options().confidence_cap(), 3.0f);
  EXPECT_EQ(decision(now, "confidence_cap")->reason().find("auto"), std::string::npos);

  // Foliage's light is found by pt's light samples: restir-gather's own cap.
  const v1::Session f = create_ok(stub(), auto_request("foliage", "auto", 32));
  ASSERT_EQ(stream_frames(stub(), f.name(), 2).size(), 2u);
  ASSERT_TRUE(get_session(stub(), f.name(), &now).ok());
  EXPECT_FLOAT_EQ(now.options().confidence_cap(), 2.0f);
  EXPECT_NE(decision(now, "confidence_cap")->reason().find("restir-gather's own cap"), std::string::npos)
      << decision(now, "confidence_cap")->reason();
}

// A resolution change makes auto calibrate again at the new size, and the frame says so.
TEST_F(MethodAutoTest, AutoCalibratesAgainWhenTheResolutionChanges) {
  const v1::Session s = create_ok(stub(), auto_request("cornell", "auto", 16));
  std::vector<v1::Frame> frames;
  StreamClient c(stub());
  const uint32_t n = service::k_auto_calibration_frames + 1;
  for (uint32_t f = 0; f < n + 1; ++f) {
    v1::FrameInput in = frame_input(f + 1, f == 0 ? s.name() : "", f);
    if (f == n) {
      in.mutable_resolution()->set_width(24);
      in.mutable_resolution()->set_height(24);
    }
    ASSERT_TRUE(c.send(in));
    auto frame = c.read();
    ASSERT_TRUE(frame.has_value());
    frames.push_back(*frame);
  }
  ASSERT_TRUE(c.close().ok());
  EXPECT_TRUE(frames.back().history_reset());
  EXPECT_NE(frames.back().history_reset_reason().find("method auto calibrates again: the resolution changed"), std::string::npos)
      << frames.back().history_reset_reason();
  v1::Session now;
  ASSERT_TRUE(get_session(stub(), s.name(), &now).ok());
  const v1::Decision* m = decision(now, "method");
  ASSERT_NE(m, nullptr);
  EXPECT_NE(m->reason().find("calibrating from frame " + std::to_string(n) + " "), std::string::npos) << m->reason();
  EXPECT_NE(m->reason().find("the resolution changed"), std::string::npos) << m->reason();
}

// Moving an instance that emits light makes auto calibrate again; moving another one does not.
TEST_F(MethodAutoTest, AutoCalibratesAgainWhenALightMoves) {
  const v1::Session s = create_ok(stub(), auto_request("cornell", "auto", 16));  // instances: room, tall_box, short_box, light
  auto moved = [](uint32_t id) {
    v1::InstanceTransform t;
    t.set_instance_id(id);
    t.mutable_translation()->set_x(0.05f);
    t.mutable_rotation()->set_w(1.0f);
    t.mutable_scale()->set_x(1.0f);
    t.mutable_scale()->set_y(1.0f);
    t.mutable_scale()->set_z(1.0f);
    return t;
  };
  StreamClient c(stub());
  const uint32_t n = service::k_auto_calibration_frames;
  std::vector<v1::Frame> frames;
  for (uint32_t f = 0; f < n + 2; ++f) {
    v1::FrameInput in = frame_input(f + 1, f == 0 ? s.name() : "");
    if (f == n) *in.add_transforms() = moved(1);      // the tall box
    if (f == n + 1) *in.add_transforms() = moved(3);  // the light
    ASSERT_TRUE(c.send(in));
    auto frame = c.read();
    ASSERT_TRUE(frame.has_value());
    frames.push_back(*frame);
  }
  ASSERT_TRUE(c.close().ok());
  EXPECT_FALSE(frames[n].history_reset()) << frames[n].history_reset_reason();
  EXPECT_TRUE(frames[n + 1].history_reset());
  EXPECT_NE(frames[n + 1].history_reset_reason().find("method auto calibrates again: instance 3, which emits light, moved"),
            std::string::npos)
      << frames[n + 1].history_reset_reason();
}

// The frames sent while calibrating are the mean of restir-gather's two runs: of a restir-gather
// session with the session's seed and of one with the second run's seed (half floats: 2e-3).
TEST_F(MethodAutoTest, CalibrationFramesAreTheMeanOfRestirGathersTwoRuns) {
  const uint32_t seed = 5;
  auto request = [&](const std::string& method, uint32_t s) {
    auto r = session_request("cornell", 16, 16, 1, s);
    r.clear_options();
    r.set_method(method);
    r.mutable_options()->set_confidence_cap(2.0f);  // what auto would choose on cornell, asked for
    return r;
  };
  const auto a = stream_frames(stub(), create_ok(stub(), request("auto", seed)).name(), 2);
  const auto first = stream_frames(stub(), create_ok(stub(), request("restir-gather", seed)).name(), 2);
  const auto second =
      stream_frames(stub(), create_ok(stub(), request("restir-gather", seed ^ service::k_auto_second_run_seed)).name(), 2);
  ASSERT_EQ(a.size(), 2u);
  ASSERT_EQ(first.size(), 2u);
  ASSERT_EQ(second.size(), 2u);
  for (size_t f = 0; f < 2; ++f) {
    const image::Image shown = frame_image(a[f]), x = frame_image(first[f]), y = frame_image(second[f]);
    ASSERT_EQ(shown.rgba.size(), x.rgba.size());
    size_t differs_from_first = 0;
    for (size_t i = 0; i < shown.rgba.size(); ++i) {
      const float mean = 0.5f * (x.rgba[i] + y.rgba[i]);
      ASSERT_NEAR(shown.rgba[i], mean, 2e-3f * std::abs(mean) + 1e-4f) << "frame " << f << " value " << i;
      differs_from_first += std::abs(shown.rgba[i] - x.rgba[i]) > 2e-3f * std::abs(x.rgba[i]) + 1e-4f;
    }
    EXPECT_GT(differs_from_first, 0u) << "frame " << f << ": the runs' streams are independent";
  }
}

// spp > 1 with auto names the method auto may choose, and pt.
TEST_F(MethodAutoTest, AutoRefusesSppAboveOneNamingWhatItMayChoose) {
  auto req = auto_request("cornell", "", 16);
  req.mutable_options()->set_spp(4);
  v1::Session out;
  const grpc::Status st = create_session(stub(), req, &out);
  EXPECT_EQ(st.error_code(), grpc::StatusCode::INVALID_ARGUMENT);
  EXPECT_NE(st.error_message().find("method auto (the default when no method is named) may choose restir-gather"),
            std::string::npos)
      << st.error_message();
  EXPECT_NE(st.error_message().find("or method = \"pt\""), std::string::npos) << st.error_message();
}

}  // namespace
}  // namespace strata::test
