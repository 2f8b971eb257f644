// The ReSTIR methods over the service: their options reach the renderer and the decisions,
// frames carry the reuse statistics (absent for pt), option changes re-create the GPU state and
// say why, and out-of-range options are INVALID_ARGUMENT naming the field and the limit. Images
// are tiny (lavapipe).
#include <algorithm>
#include <cmath>

#include "harness.h"
#include "render/renderer.h"

namespace strata::test {
namespace {

using grpc::StatusCode;
using RestirTest = ServiceTest;

v1::CreateSessionRequest restir_request(const std::string& method, uint32_t width = 16, uint32_t height = 16) {
  auto r = session_request("cornell", width, height);
  r.clear_options();  // the default spp (1) is what the restir-* methods take
  r.set_method(method);
  return r;
}

uint64_t counter(const v1::ReuseStatistics& r, const std::string& key) {
  auto it = r.counters().find(key);
  return it == r.counters().end() ? 0 : it->second;
}

void expect_status(const grpc::Status& st, StatusCode code, const std::string& message, const std::string& what) {
  EXPECT_EQ(st.error_code(), code) << what << ": " << st.error_message();
  EXPECT_NE(st.error_message().find(message), std::string::npos)
      << what << ": message '" << st.error_message() << "' does not contain '" << message << "'";
}

const char* const k_restir_options[] = {"shift",           "mis",          "unbiased",          "confidence_cap",
                                        "temporal_reuse",  "spatial_reuse", "spatial_neighbors", "spatial_radius",
                                        "initial_candidates", "light_candidates", "disocclusion_spatial_neighbors",
                                        "direct_strata", "temporal_filter", "still_confidence_cap"};

TEST_F(RestirTest, GatherSessionReportsItsOptionsAndStreamsReuseStatistics) {
  auto req = restir_request("restir-gather");
  req.mutable_options()->set_light_candidates(2);
  const v1::Session s = create_ok(stub(), req);
  ASSERT_FALSE(s.name().empty());
  EXPECT_EQ(s.method(), "restir-gather");
  // Effective options: the renderer's defaults (docs/ARCHITECTURE.md, Methods) and what was asked.
  EXPECT_EQ(s.options().spp(), 1u);
  EXPECT_EQ(s.options().experimental().shift(), v1::SHIFT_HYBRID);
  EXPECT_EQ(s.options().experimental().mis(), v1::MIS_PAIRWISE);
  EXPECT_FLOAT_EQ(s.options().confidence_cap(), 2.0f);  // restir-gather's (method_table.cpp)
  EXPECT_FLOAT_EQ(s.options().still_confidence_cap(), 8.0f);
  EXPECT_EQ(s.options().spatial_neighbors(), 2u);
  // Not requested: from the image height, 2.5% with a floor of 4 px (16 px high: the floor).
  EXPECT_FLOAT_EQ(s.options().spatial_radius(), render::RestirOptions::default_spatial_radius(16));
  EXPECT_FLOAT_EQ(s.options().spatial_radius(), 4.0f);
  EXPECT_FLOAT_EQ(create_ok(stub(), restir_request("restir-gather", 16, 400)).options().spatial_radius(), 10.0f);
  EXPECT_EQ(s.options().initial_candidates(), 1u);
  EXPECT_EQ(s.options().light_candidates(), 2u);
  EXPECT_TRUE(s.options().temporal_reuse());
  EXPECT_TRUE(s.options().spatial_reuse());
  EXPECT_TRUE(s.options().experimental().unbiased());
  EXPECT_EQ(s.options().disocclusion_spatial_neighbors(), 6u);
  EXPECT_EQ(s.options().direct_strata(), 3u);
  EXPECT_TRUE(s.options().experimental().temporal_filter());
  for (const char* name : k_restir_options) {
    const v1::Decision* d = decision(s, name);
    ASSERT_NE(d, nullptr) << name;
    EXPECT_TRUE(d->applies()) << name << ": " << d->reason();
  }
  EXPECT_EQ(decision(s, "light_candidates")->requested(), "2");
  EXPECT_EQ(decision(s, "light_candidates")->value(), "2");
  EXPECT_EQ(decision(s, "spatial_neighbors")->requested(), "");
  EXPECT_EQ(decision(s, "spatial_neighbors")->value(), "2");

  const auto frames = stream_frames(stub(), s.name(), 3);
  ASSERT_EQ(frames.size(), 3u);
  for (size_t i = 0; i < frames.size(); ++i) {
    SCOPED_TRACE("frame " + std::to_string(i));
    const v1::Frame& f = frames[i];
    EXPECT_EQ(f.history_reset(), i == 0);
    const auto& st = f.statistics();
    ASSERT_TRUE(st.has_reuse()) << "restir-gather reports reuse statistics";
    const auto& reuse = st.reuse();
    EXPECT_TRUE(reuse.counters().contains("temporal.shifts"));
    EXPECT_TRUE(reuse.counters().contains("spatial.shifts"));
    for (const auto& [key, n] : reuse.shift_failures())
      EXPECT_TRUE(key.rfind("temporal.", 0) == 0 || key.rfind("spatial.", 0) == 0) << key;
    if (i > 0) {
      EXPECT_GT(counter(reuse, "temporal.shifts"), 0u) << "the previous frame's reservoirs were not reused";
    }
    EXPECT_TRUE(st.rays_traced().contains("initial")) << "ReSTIR counts rays by pass";
    EXPECT_GT(st.rays_total(), 0u);
    const image::Image img = frame_image(f);
    double sum = 0.0;
    for (float v : img.rgba) {
      ASSERT_TRUE(std::isfinite(v));
      sum += v;
    }
    EXPECT_GT(sum, 0.0) << "black frame";
  }

  // The same server's pt sessions report no reuse, and the ReSTIR options do not apply to them.
  auto pt_req = session_request("cornell", 16, 16);
  pt_req.mutable_options()->set_spatial_neighbors(4);
  const v1::Session pt = create_ok(stub(), pt_req);
  for (const char* name : k_restir_options) {
    const v1::Decision* d = decision(pt, name);
    ASSERT_NE(d, nullptr) << name;
    EXPECT_FALSE(d->applies()) << name;
  }
  const auto pt_frames = stream_frames(stub(), pt.name(), 1);
  ASSERT_EQ(pt_frames.size(), 1u);
  EXPECT_FALSE(pt_frames[0].statistics().has_reuse()) << "pt reports no reuse statistics";
}

TEST_F(RestirTest, DirectLightingSessionStreamsReuseStatistics) {
  const v1::Session s = create_ok(stub(), restir_request("restir-di"));
  EXPECT_EQ(s.method(), "restir-di");
  const v1::Decision* method = decision(s, "method");
  ASSERT_NE(method, nullptr);
  EXPECT_NE(method->reason().find("ReSTIR DI"), std::string::npos) << method->reason();
  EXPECT_TRUE(decision(s, "light_candidates")->applies());
  const auto frames = stream_frames(stub(), s.name(), 2);
  ASSERT_EQ(frames.size(), 2u);
  ASSERT_TRUE(frames[1].statistics().has_reuse());
  EXPECT_GT(counter(frames[1].statistics().reuse(), "temporal.shifts"), 0u);
}

TEST_F(RestirTest, OptionChangesRecreateTheGpuStateAndSayWhy) {
  auto req = restir_request("restir-gather");
  req.mutable_options()->set_spatial_reuse(false);
  const v1::Session s = create_ok(stub(), req);
  EXPECT_FALSE(s.options().spatial_reuse());
  EXPECT_EQ(decision(s, "spatial_reuse")->value(), "off");
  EXPECT_FALSE(decision(s, "spatial_radius")->applies()) << "spatial reuse is off";
  EXPECT_TRUE(decision(s, "confidence_cap")->applies());

  // Each option change compiles the passes it newly needs: from a fresh clone (an empty shader
  // cache) on a loaded 2-core machine that took more than the default 60 s once.
  StreamClient c(stub(), 300s);
  ASSERT_TRUE(c.send(frame_input(1, s.name(), 0)));
  auto f1 = c.read();
  ASSERT_TRUE(f1);
  ASSERT_TRUE(f1->statistics().has_reuse());

  v1::FrameInput same = frame_input(2, "", 0);
  ASSERT_TRUE(c.send(same));
  auto f2 = c.read();
  ASSERT_TRUE(f2);
  EXPECT_FALSE(f2->history_reset());
  EXPECT_GT(counter(f2->statistics().reuse(), "temporal.shifts"), 0u);

  v1::FrameInput change = frame_input(3, "", 0);
  change.mutable_options()->set_spatial_reuse(true);
  change.mutable_options()->set_spatial_neighbors(3);
  ASSERT_TRUE(c.send(change));
  auto f3 = c.read();
  ASSERT_TRUE(f3);
  EXPECT_TRUE(f3->history_reset());
  EXPECT_NE(f3->history_reset_reason().find("spatial_neighbors changed from 2 to 3"), std::string::npos)
      << f3->history_reset_reason();
  EXPECT_NE(f3->history_reset_reason().find("spatial_reuse changed from false to true"), std::string::npos)
      << f3->history_reset_reason();

  v1::Session after;
  ASSERT_TRUE(get_session(stub(), s.name(), &after).ok());
  EXPECT_EQ(after.options().spatial_neighbors(), 3u);
  EXPECT_TRUE(after.options().spatial_reuse());
  EXPECT_EQ(decision(after, "spatial_neighbors")->requested(), "3");
  EXPECT_TRUE(decision(after, "spatial_radius")->applies());

  // spp != 1 in an option change ends the stream with INVALID_ARGUMENT before anything renders.
  v1::FrameInput spp = frame_input(4, "", 0);
  spp.mutable_options()->set_spp(4);
  c.send(spp);
  EXPECT_FALSE(c.read()) << "spp = 4 was rendered by restir-gather";
  expect_status(c.finish(), StatusCode::INVALID_ARGUMENT, "options.spp = 4", "spp change");
  ASSERT_TRUE(wait_until([&] {
    v1::Session v;
    return get_session(stub(), s.name(), &v).ok() && v.state() == v1::Session::IDLE;
  }, 10s));
  v1::Session kept;
  ASSERT_TRUE(get_session(stub(), s.name(), &kept).ok());
  EXPECT_EQ(kept.options().spp(), 1u) << "the refused input changed the session";
}

// A session that names no method gets the default, auto (service/method_auto.h), which calibrates
// with restir-gather's options, and its decision says so; spp != 1 then names what auto may choose
// and pt.
TEST_F(RestirTest, SessionWithoutAMethodGetsTheDefaultAndSaysWhy) {
  const v1::Session s = create_ok(stub(), restir_request(""));
  EXPECT_EQ(s.method(), "restir-gather");
  const v1::Decision* method = decision(s, "method");
  ASSERT_NE(method, nullptr);
  EXPECT_EQ(method->requested(), "");
  EXPECT_EQ(method->value(), "restir-gather");
  EXPECT_NE(method->reason().find("auto: calibrating"), std::string::npos) << method->reason();
  const auto frames = stream_frames(stub(), s.name(), 2);
  ASSERT_EQ(frames.size(), 2u);
  EXPECT_TRUE(frames[1].statistics().has_reuse());

  const v1::Session named = create_ok(stub(), restir_request("restir-gather"));
  EXPECT_EQ(decision(named, "method")->requested(), "restir-gather");
  EXPECT_EQ(decision(named, "method")->reason().find("auto"), std::string::npos);

  auto spp = restir_request("");
  spp.mutable_options()->set_spp(4);
  v1::Session refused;
  expect_status(create_session(stub(), spp, &refused), StatusCode::INVALID_ARGUMENT,
                "options.spp = 4 but method auto (the default when no method is named) may choose restir-gather",
                "spp 4 without a method");
  expect_status(create_session(stub(), spp, &refused), StatusCode::INVALID_ARGUMENT, "or method = \"pt\"",
                "spp 4 without a method");

  // The same in an option change of a stream on the defaulted session, once the server has
  // detached the first stream (its reactor finishes after the client's; under load that lags).
  ASSERT_TRUE(wait_until(
      [&] {
        v1::Session now;
        return get_session(stub(), s.name(), &now).ok() && now.state() == v1::Session::IDLE;
      },
      30s));
  StreamClient c(stub());
  v1::FrameInput change = frame_input(1, s.name(), 0);
  change.mutable_options()->set_spp(4);
  c.send(change);
  EXPECT_FALSE(c.read()) << "spp = 4 was rendered by the default method";
  expect_status(c.finish(), StatusCode::INVALID_ARGUMENT, "method auto (the default when no method is named)",
                "spp change without a method");
}

// The confidence cap where something moved is the method's unless asked for (render::MethodSpec::
// confidence_cap): 2 for the splat methods, whose history under motion carries the noise of how many
// splats land in a pixel (docs/BENCHMARKS.md); the decision says so. The still cap applies to them too.
TEST_F(RestirTest, SplatSessionsGetTheirMethodsConfidenceCapAndSayWhy) {
  for (const char* method : {"restir-splat", "restir-splat-backup"}) {
    const v1::Session s = create_ok(stub(), restir_request(method));
    EXPECT_FLOAT_EQ(s.options().confidence_cap(), 2.0f) << method;
    EXPECT_FLOAT_EQ(s.options().still_confidence_cap(), 8.0f) << method;
    const v1::Decision* cap = decision(s, "confidence_cap");
    ASSERT_NE(cap, nullptr);
    EXPECT_EQ(cap->value(), "2");
    EXPECT_NE(cap->reason().find("how many splats land in a pixel"), std::string::npos) << cap->reason();
    EXPECT_TRUE(decision(s, "still_confidence_cap")->applies()) << method;
  }
  auto asked = restir_request("restir-splat");
  asked.mutable_options()->set_confidence_cap(6.0f);
  const v1::Session s = create_ok(stub(), asked);
  EXPECT_FLOAT_EQ(s.options().confidence_cap(), 6.0f);
  EXPECT_EQ(decision(s, "confidence_cap")->reason().find("splats land"), std::string::npos);
  const auto frames = stream_frames(stub(), s.name(), 2);
  ASSERT_EQ(frames.size(), 2u);
  EXPECT_GT(counter(frames[1].statistics().reuse(), "splat.landed"), 0u);
}

TEST_F(RestirTest, BadRestirOptionsAreInvalidArgumentNamingTheField) {
  struct Case {
    std::string what;
    v1::CreateSessionRequest request;
    std::string message;
  };
  std::vector<Case> cases;
  auto add = [&](std::string what, const std::string& method, auto edit, std::string message) {
    v1::CreateSessionRequest r = restir_request(method);
    edit(*r.mutable_options());
    cases.push_back({std::move(what), std::move(r), std::move(message)});
  };
  add("spatial_neighbors 9", "restir-gather", [](auto& o) { o.set_spatial_neighbors(9); },
      "options.spatial_neighbors = 9 is outside [0, 8] (limit RESTIR_MAX_SPATIAL_NEIGHBORS)");
  add("spatial_radius 0", "restir-gather", [](auto& o) { o.set_spatial_radius(0.0f); },
      "options.spatial_radius = 0 is outside [1, 256]");
  add("spatial_radius 300", "restir-gather", [](auto& o) { o.set_spatial_radius(300.0f); },
      "options.spatial_radius = 300 is outside [1, 256]");
  add("initial_candidates 0", "restir-gather", [](auto& o) { o.set_initial_candidates(0); },
      "options.initial_candidates = 0 is outside [1, 64]");
  add("initial_candidates 65", "restir-gather", [](auto& o) { o.set_initial_candidates(65); },
      "options.initial_candidates = 65 is outside [1, 64]");
  add("light_candidates 33", "restir-gather", [](auto& o) { o.set_light_candidates(33); },
      "options.light_candidates = 33 is outside [1, 32]");
  add("light_candidates 0", "restir-di", [](auto& o) { o.set_light_candidates(0); },
      "options.light_candidates = 0 is outside [1, 32]");
  add("disocclusion_spatial_neighbors 9", "restir-gather", [](auto& o) { o.set_disocclusion_spatial_neighbors(9); },
      "options.disocclusion_spatial_neighbors = 9 is outside [0, 8] (0 = spatial_neighbors; limit RESTIR_MAX_SPATIAL_NEIGHBORS)");
  add("hole_fill_radius 9", "restir-multilayer", [](auto& o) { o.set_hole_fill_radius(9); },
      "options.hole_fill_radius = 9 is outside [0, 8] pixels (0 = off; limit RESTIR_MAX_HOLE_FILL_RADIUS)");
  add("silhouette_band 33", "restir-multilayer", [](auto& o) { o.set_silhouette_band(33); },
      "options.silhouette_band = 33 is outside [0, 32] pixels (0 = off; limit RESTIR_MAX_SILHOUETTE_BAND)");
  add("reveal_lookahead 17", "restir-multilayer", [](auto& o) { o.set_reveal_lookahead(17); },
      "options.reveal_lookahead = 17 is outside [0, 16] frames (0 = off; limit RESTIR_MAX_REVEAL_LOOKAHEAD)");
  add("direct_strata 0", "restir-gather", [](auto& o) { o.set_direct_strata(0); },
      "options.direct_strata = 0 is outside [1, 8]");
  add("direct_strata 9", "restir-splat", [](auto& o) { o.set_direct_strata(9); },
      "options.direct_strata = 9 is outside [1, 8]");
  add("confidence_cap 0.5", "restir-gather", [](auto& o) { o.set_confidence_cap(0.5f); },
      "options.confidence_cap = 0.5 is outside [1, 1000]");
  add("confidence_cap 1001", "restir-gather", [](auto& o) { o.set_confidence_cap(1001.0f); },
      "options.confidence_cap = 1001 is outside [1, 1000]");
  add("still_confidence_cap 0.5", "restir-gather", [](auto& o) { o.set_still_confidence_cap(0.5f); },
      "options.still_confidence_cap = 0.5 is outside [1, 1000] (0 = confidence_cap; limit RESTIR_MAX_CONFIDENCE_CAP)");
  add("still_confidence_cap NaN", "restir-gather", [](auto& o) { o.set_still_confidence_cap(std::nanf("")); },
      "options.still_confidence_cap = nan is outside [1, 1000]");
  add("shift not an enum value", "restir-gather", [](auto& o) { o.mutable_experimental()->set_shift(static_cast<v1::Shift>(9)); },
      "options.experimental.shift = 9 is not one of SHIFT_RECONNECTION, SHIFT_HYBRID");
  add("mis not an enum value", "restir-gather", [](auto& o) { o.mutable_experimental()->set_mis(static_cast<v1::Mis>(5)); },
      "options.experimental.mis = 5 is not one of MIS_BALANCE, MIS_PAIRWISE");
  add("restir-gather with spp 4", "restir-gather", [](auto& o) { o.set_spp(4); }, "options.spp = 4");
  add("restir-di with spp 2", "restir-di", [](auto& o) { o.set_spp(2); }, "options.spp = 2");
  add("pt with spatial_neighbors 9", "pt", [](auto& o) { o.set_spatial_neighbors(9); },
      "options.spatial_neighbors = 9 is outside [0, 8]");

  for (const auto& c : cases) {
    v1::Session s;
    expect_status(create_session(stub(), c.request, &s), StatusCode::INVALID_ARGUMENT, c.message, c.what);
  }
  v1::Session s;
  const auto spp_case = std::find_if(cases.begin(), cases.end(), [](const auto& c) { return c.what == "restir-gather with spp 4"; });
  ASSERT_NE(spp_case, cases.end());
  const grpc::Status spp = create_session(stub(), spp_case->request, &s);
  EXPECT_NE(spp.error_message().find("spp must be 1"), std::string::npos) << spp.error_message();
  EXPECT_EQ(server_status(stub()).sessions(), 0u) << "a refused request left a session";
  // pt takes any spp within max_spp.
  auto pt = session_request("cornell", 16, 16, 4);
  EXPECT_TRUE(create_session(stub(), pt, &s).ok());
}

}  // namespace
}  // namespace strata::test
