// The option table (server/options/option_table.h) against what it describes: the proto's
// RenderOptions and ExperimentalOptions fields, the flags of `stratad render` and `strata
// stream/eval/loadtest`, docs/OPTIONS.md; and a mid-stream change of every option, which either
// reaches the device from that frame on (the frame names it) or is reported as not applying.
// GPU cases run on lavapipe at 32 x 32.
#include <algorithm>
#include <fstream>
#include <map>
#include <set>

#include "options/option_docs.h"
#include "options/option_flags.h"
#include "options/option_proto.h"
#include "process.h"
#include "render/method_table.h"
#include "scene/scene_io.h"
#include "service/options.h"

namespace strata::test {
namespace {

using google::protobuf::FieldDescriptor;

// "LAYER_MODE_NO_DEPTH_RANGES" ends with the choice "no-depth-ranges" written in upper case.
bool names_choice(const std::string& enum_value, std::string choice) {
  for (char& c : choice) c = c == '-' ? '_' : char(std::toupper(static_cast<unsigned char>(c)));
  return enum_value.size() > choice.size() && enum_value.compare(enum_value.size() - choice.size(), choice.size(), choice) == 0 &&
         enum_value[enum_value.size() - choice.size() - 1] == '_';
}

TEST(OptionTable, EveryProtoFieldIsOneRowOfItsGroup) {
  std::set<std::string> rows;
  for (const auto& o : options::option_table()) {
    SCOPED_TRACE(o.name);
    EXPECT_TRUE(rows.insert(o.name).second) << "two rows";
    const FieldDescriptor* f = options::proto_field(o);
    ASSERT_NE(f, nullptr) << "no field " << options::field_path(o, "RenderOptions") << " in render.proto";
    EXPECT_TRUE(f->has_presence()) << "the field must be optional: a FrameInput changes only the fields that are set";
    const auto type = f->cpp_type();
    switch (o.kind) {
      case options::Kind::count: EXPECT_EQ(type, FieldDescriptor::CPPTYPE_UINT32); break;
      case options::Kind::real: EXPECT_EQ(type, FieldDescriptor::CPPTYPE_FLOAT); break;
      case options::Kind::flag: EXPECT_EQ(type, FieldDescriptor::CPPTYPE_BOOL); break;
      case options::Kind::choice: {
        ASSERT_EQ(type, FieldDescriptor::CPPTYPE_ENUM);
        const auto* e = f->enum_type();
        EXPECT_EQ(e->value(0)->number(), 0) << "UNSPECIFIED first";
        ASSERT_EQ(size_t(e->value_count() - 1), o.choices.size()) << "a choice per enum value but UNSPECIFIED";
        for (const auto& c : o.choices) {
          const auto* v = e->FindValueByNumber(c.proto);
          ASSERT_NE(v, nullptr) << c.name;
          EXPECT_TRUE(names_choice(std::string(v->name()), c.name)) << v->name() << " is not choice " << c.name;
        }
        break;
      }
    }
    // The default is a value of the option, and the flag writes the option's name.
    render::RestirOptions defaults;
    if (o.set) {
      EXPECT_EQ(o.get(defaults), options::default_value(o));
    }
    std::string flag = o.name;
    std::replace(flag.begin(), flag.end(), '_', '-');
    if (!o.negated_flag) {
      EXPECT_EQ(std::string(o.flag), "--" + flag);
    }
    EXPECT_FALSE(std::string(o.help).empty());
  }
  EXPECT_NO_THROW(render::RestirOptions{}.validate());
  // And the other way: every field of both messages has its row, in its group.
  auto check_message = [&](const google::protobuf::Descriptor* d, options::Group group) {
    for (int i = 0; i < d->field_count(); ++i) {
      const std::string name(d->field(i)->name());
      if (d == v1::RenderOptions::descriptor() && name == "experimental") continue;
      const options::OptionSpec* o = options::find_option(name);
      ASSERT_NE(o, nullptr) << d->name() << "." << name << " has no row in the option table";
      EXPECT_EQ(o->group, group) << name;
    }
  };
  check_message(v1::RenderOptions::descriptor(), options::Group::user);
  check_message(v1::ExperimentalOptions::descriptor(), options::Group::experimental);
}

// The flags of both programs come from the table: each command lists every user flag in --help
// and every experimental one in --help-experimental only, with the same help line.
TEST(OptionTable, EveryCommandHasTheTablesFlags) {
  struct Command {
    std::vector<std::string> argv;
    std::set<std::string> own;  // options the command defines itself
  };
  const std::set<std::string> own = {"spp", "max_depth", "exposure"};
  std::set<std::string> eval_own = own;
  eval_own.insert("splats_per_frame");
  const std::vector<Command> commands = {{{stratad_path(), "render"}, own},
                                         {{strata_path(), "stream"}, own},
                                         {{strata_path(), "eval"}, eval_own},
                                         {{strata_path(), "loadtest"}, own}};
  for (const auto& c : commands) {
    SCOPED_TRACE(c.argv[0] + " " + c.argv[1]);
    auto args = c.argv;
    args.push_back("--help");
    const ProcessResult help = run_process(args, 30s);
    ASSERT_EQ(help.exit_code, 0) << help.output;
    args.back() = "--help-experimental";
    const ProcessResult experimental = run_process(args, 30s);
    ASSERT_EQ(experimental.exit_code, 0) << experimental.output;
    for (const auto& o : options::option_table()) {
      SCOPED_TRACE(o.name);
      const std::string line = options::flag_help(o);
      const bool user = o.group == options::Group::user;
      if (c.own.count(o.name)) continue;  // the command's own flag, or none (eval's spp is per method)
      EXPECT_EQ(help.output.find(line) != std::string::npos, user) << help.output;
      EXPECT_EQ(help.output.find(std::string(o.flag) + " ") != std::string::npos, user);
      EXPECT_EQ(experimental.output.find(line) != std::string::npos, !user) << experimental.output;
    }
  }
  // A value outside the table's range is refused by the flag, naming it and the limit.
  const ProcessResult bad = run_process({stratad_path(), "render", "--layers", "9"}, 30s);
  EXPECT_NE(bad.exit_code, 0);
  EXPECT_NE(bad.output.find("--layers = 9 is outside [0, 8]"), std::string::npos) << bad.output;
}

TEST(OptionTable, OptionsMdIsGeneratedFromTheTable) {
  std::ifstream in(std::string(STRATA_SOURCE_DIR) + "/docs/OPTIONS.md", std::ios::binary);
  const std::string checked_in((std::istreambuf_iterator<char>(in)), {});
  EXPECT_EQ(checked_in, options::options_markdown())
      << "docs/OPTIONS.md is not the table's: run `stratad options --markdown > docs/OPTIONS.md`";
  const ProcessResult generated = run_process({stratad_path(), "options", "--markdown"}, 30s);
  ASSERT_EQ(generated.exit_code, 0);
  EXPECT_EQ(generated.output, checked_in);
}

// ---------------------------------------------------------------------------------------------
// Mid-stream changes on the device.

class OptionChangeTest : public ServiceTest {
 protected:
  void check_every_change(options::Group group);
};

// A stream whose first frame compiles pipelines no earlier case needed (layer_mode uniform: the layer
// stepping variants) takes minutes on lavapipe on a loaded 2-core machine.
constexpr std::chrono::seconds k_change_deadline = 900s;

const v1::Decision* change(const v1::Frame& f, const std::string& name) {
  for (const auto& d : f.option_changes())
    if (d.name() == name) return &d;
  return nullptr;
}

uint64_t reuse_counter(const v1::Frame& f, const std::string& key) {
  const auto& c = f.statistics().reuse().counters();
  auto it = c.find(key);
  return it == c.end() ? 0 : it->second;
}

std::string pass_reason(const v1::Frame& f, const std::string& pass) {
  for (const auto& p : f.statistics().passes())
    if (p.pass() == pass) return std::string(p.ran() ? "ran: " : "left out: ") + p.reason();
  return "(no pass " + pass + ")";
}

// The case: restir-multilayer on carousel with 3 layers; from frame 3 on the input asks for 1.
TEST_F(OptionChangeTest, LayersChangeMidStreamRendersOneLayerFromThatFrame) {
  auto req = session_request("carousel", 32, 32);
  req.clear_options();
  req.set_method("restir-multilayer");
  req.mutable_options()->set_layers(3);
  const v1::Session s = create_ok(stub(), req);
  StreamClient c(stub(), k_change_deadline);
  std::vector<v1::Frame> frames;
  for (uint32_t i = 0; i < 6; ++i) {
    v1::FrameInput in = frame_input(i + 1, i == 0 ? s.name() : "", i);
    if (i == 3) in.mutable_options()->set_layers(1);
    ASSERT_TRUE(c.send(in));
    auto f = c.read();
    ASSERT_TRUE(f);
    frames.push_back(*f);
  }
  ASSERT_TRUE(c.close().ok());
  EXPECT_GT(reuse_counter(frames[2], "domains.active_layer_1"), 0u) << "three layers before the change";
  EXPECT_NE(pass_reason(frames[2], "domain_init").find("3 layers"), std::string::npos) << pass_reason(frames[2], "domain_init");
  // On the device: no deep layer from the change on.
  for (size_t i = 3; i < frames.size(); ++i) {
    SCOPED_TRACE("frame " + std::to_string(i));
    EXPECT_EQ(reuse_counter(frames[i], "domains.active_layer_1"), 0u) << "a deep layer after layers = 1";
    EXPECT_EQ(pass_reason(frames[i], "domain_init").find("3 layers"), std::string::npos) << pass_reason(frames[i], "domain_init");
  }
  // And the frame says so.
  EXPECT_TRUE(frames[3].history_reset());
  EXPECT_NE(frames[3].history_reset_reason().find("layers changed from 3 to 1"), std::string::npos)
      << frames[3].history_reset_reason();
  const v1::Decision* d = change(frames[3], "layers");
  EXPECT_TRUE(d && d->applies()) << "frame 3's option_changes do not report layers as applied";
  v1::Session after;
  ASSERT_TRUE(get_session(stub(), s.name(), &after).ok());
  EXPECT_EQ(after.options().layers(), 1u);
  EXPECT_EQ(decision(after, "layers")->value(), "1");
}

// A value other than the row's default, within its range: what the change sets.
double other_value(const options::OptionSpec& o, double current) {
  switch (o.kind) {
    case options::Kind::flag: return current != 0.0 ? 0.0 : 1.0;
    case options::Kind::choice:
      for (const auto& c : o.choices)
        if (double(c.value) != current) return double(c.value);
      return current;
    default: break;
  }
  if (o.hi == 0.0) return current == o.lo ? o.lo + 1.0 : o.lo;  // spp, max_depth: held to the service's limits
  return current != o.hi ? o.hi : o.lo;
}

struct Rendered {
  std::vector<v1::Frame> frames;
  image::Image last;
};

// How the three frames move, so that an option's effect can show.
struct Motion {
  bool lod_switches = false;  // every instance with LoD levels switches between levels 0 and 1 each frame
  bool shutter = false;       // the scene's animated camera with the shutter open (motion blur)
};

// Three frames of `method` on `scene` (32 x 32) with the animation running; the first input changes
// `option` to `value` (when given): the renderer created with the session is re-created before frame 0.
Rendered render_with(v1::RenderService::Stub& stub, const std::string& method, const std::string& scene, Motion motion,
                     const options::OptionSpec* option, double value) {
  auto req = session_request(scene, 32, 32, 1, 7, {v1::IMAGE_ENCODING_RAW_RGBA16F, v1::IMAGE_ENCODING_PNG_PREVIEW});
  req.clear_options();
  req.set_method(method);
  if (render::method_spec(method).layers) req.mutable_options()->set_layers(3);  // not auto: a small image may measure one
  const v1::Session s = create_ok(stub, req);
  const scene::Scene model = scene::builtin_scene(scene);
  Rendered r;
  StreamClient c(stub, k_change_deadline);
  for (uint32_t i = 0; i < 3; ++i) {
    v1::FrameInput in = frame_input(i + 1, i == 0 ? s.name() : "", 4 * i);
    if (option && i == 0) options::set_value(*in.mutable_options(), *option, value);
    if (motion.lod_switches)
      for (const auto& instance : s.analysis().instances())
        if (instance.lod_levels() > 1) {
          auto* l = in.add_lod_changes();
          l->set_instance_id(instance.id());
          l->set_level(i % 2);
        }
    if (motion.shutter) {
      const scene::Camera cam = model.frame_state(4 * i).camera;
      auto* out = in.mutable_camera();
      out->mutable_position()->set_x(cam.position.x);
      out->mutable_position()->set_y(cam.position.y);
      out->mutable_position()->set_z(cam.position.z + 0.2f * float(i));
      out->mutable_orientation()->set_w(cam.orientation.w);
      out->mutable_orientation()->set_x(cam.orientation.x);
      out->mutable_orientation()->set_y(cam.orientation.y);
      out->mutable_orientation()->set_z(cam.orientation.z);
      out->set_vertical_fov(cam.yfov);
      out->set_shutter(1.0f);
    }
    EXPECT_TRUE(c.send(in));
    auto f = c.read();
    if (!f) break;
    r.frames.push_back(*f);
  }
  const grpc::Status st = c.close();
  EXPECT_TRUE(st.ok()) << st.error_message();
  EXPECT_EQ(r.frames.size(), 3u);
  if (!r.frames.empty()) r.last = frame_image(r.frames.back());
  EXPECT_TRUE(delete_session(stub, s.name()).ok());
  return r;
}

// Every option of the table, changed by a FrameInput on a session of a method it applies to: the
// frame reports the change with what it did, and what the device renders differs from the same
// stream without the change (a change the renderer kept out would leave the frames bit-identical).
// Where a method it does not apply to gets the change, the frame reports it as not applying and
// nothing is re-created (OptionsOfOtherMethodsAreReportedAsNotApplying).
void OptionChangeTest::check_every_change(options::Group group) {
  // The method and scene where each option shows (the first that it applies to, unless named).
  const std::map<std::string, std::pair<std::string, std::string>> where = {
      {"spp", {"pt", "carousel"}}, {"max_depth", {"pt", "carousel"}}, {"still_confidence_cap", {"restir-gather", "cornell"}},
      {"lod_mapping", {"restir-gather", "lod-cliff"}},  {"lod_matching", {"restir-splat", "overlap-uv"}},
      {"lod_vertices", {"restir-gather", "lod-cliff"}}, {"albedo_strata", {"restir-gather", "chess"}},
  };
  // The value it changes to, where the row's other end of the range would show nothing.
  const std::map<std::string, std::string> values = {{"suffix", "fail"},        {"view_layer", "1"},      {"layers", "1"},
                                                     {"silhouette_band", "0"},  {"reveal_lookahead", "0"}, {"still_confidence_cap", "1"},
                                                     {"light_sampler", "tree"}};  // auto is power on carousel
  const std::set<std::string> lod = {"lod_mapping", "lod_matching", "lod_vertices"};
  const std::vector<std::string> methods = {"restir-gather", "restir-splat", "restir-multilayer", "pt"};
  std::map<std::string, Rendered> controls;
  for (const auto& o : options::option_table()) {
    if (o.group != group) continue;
    SCOPED_TRACE(o.name);
    std::string method, scene = "carousel";
    if (auto it = where.find(o.name); it != where.end()) {
      std::tie(method, scene) = it->second;
    } else {
      for (const auto& m : methods)
        if (options::applies(o, render::method_spec(m))) {
          method = m;
          break;
        }
    }
    ASSERT_FALSE(method.empty());
    const Motion motion{.lod_switches = lod.count(o.name) > 0, .shutter = std::string(o.name) == "splats_per_frame"};
    const std::string key = method + "/" + scene + (motion.lod_switches ? "/lod" : "") + (motion.shutter ? "/shutter" : "");
    if (!controls.count(key)) controls[key] = render_with(stub(), method, scene, motion, nullptr, 0.0);
    const Rendered& control = controls[key];
    v1::RenderOptions requested;
    if (render::method_spec(method).layers) requested.set_layers(3);
    const v1::RenderOptions defaults = service::with_defaults(requested, render::method_spec(method), config_.limits, 32);
    const auto named = values.find(o.name);
    const double value = named != values.end() ? *options::parse_value(o, named->second)
                                               : other_value(o, options::get_value(defaults, o));
    const Rendered changed = render_with(stub(), method, scene, motion, &o, value);
    ASSERT_EQ(changed.frames.size(), 3u);
    const v1::Frame& first = changed.frames[0];
    const v1::Decision* d = change(first, o.name);
    ASSERT_NE(d, nullptr) << "frame 0 does not report the change";
    EXPECT_TRUE(d->applies()) << d->reason();
    if (o.on_change == options::OnChange::recreate) {
      EXPECT_NE(first.history_reset_reason().find(std::string(o.name) + " changed from"), std::string::npos)
          << first.history_reset_reason();
    }
    // On the device: the image (for exposure the PNG preview), else the frames' reuse counters or
    // pass reasons (what the passes did: dormant domains, time partitions, ...).
    const auto png = [](const v1::Frame& f) { return find_image(f, v1::IMAGE_ENCODING_PNG_PREVIEW)->data(); };
    const auto trace = [](const Rendered& r) {
      std::string t;
      for (const auto& f : r.frames) {
        for (const auto& p : f.statistics().passes()) t += p.pass() + (p.ran() ? " ran: " : " out: ") + p.reason() + "\n";
        for (const auto& [k, v] : std::map<std::string, uint64_t>(f.statistics().reuse().counters().begin(),
                                                                   f.statistics().reuse().counters().end()))
          t += k + " = " + std::to_string(v) + "\n";
      }
      return t;
    };
    const bool differs = o.on_change == options::OnChange::in_place ? png(changed.frames.back()) != png(control.frames.back())
                                                                     : changed.last.rgba != control.last.rgba ||
                                                                           trace(changed) != trace(control);
    EXPECT_TRUE(differs) << method << " on " << scene << ": " << o.name << " = " << options::value_text(o, value)
                         << " renders what the default does";
    EXPECT_TRUE(changed.frames[1].option_changes().empty()) << "the change is reported once";
  }
}

TEST_F(OptionChangeTest, EveryUserOptionChangeReachesTheDevice) { check_every_change(options::Group::user); }

TEST_F(OptionChangeTest, EveryExperimentalOptionChangeReachesTheDevice) { check_every_change(options::Group::experimental); }

TEST_F(OptionChangeTest, OptionsOfOtherMethodsAreReportedAsNotApplying) {
  // On pt, the restir-* options are reported as not applying, and nothing is re-created.
  auto req = session_request("cornell", 16, 16);
  const v1::Session s = create_ok(stub(), req);
  StreamClient c(stub());
  ASSERT_TRUE(c.send(frame_input(1, s.name(), 0)));
  ASSERT_TRUE(c.read());
  v1::FrameInput in = frame_input(2, "", 0);
  in.mutable_options()->set_layers(2);
  in.mutable_options()->mutable_experimental()->set_shift(v1::SHIFT_RECONNECTION);
  ASSERT_TRUE(c.send(in));
  auto f = c.read();
  ASSERT_TRUE(f);
  ASSERT_TRUE(c.close().ok());
  EXPECT_FALSE(f->history_reset()) << f->history_reset_reason();
  for (const char* name : {"layers", "shift"}) {
    const v1::Decision* d = change(*f, name);
    ASSERT_NE(d, nullptr) << name;
    EXPECT_FALSE(d->applies()) << name;
    EXPECT_NE(d->reason().find("method pt"), std::string::npos) << d->reason();
  }
  v1::Session after;
  ASSERT_TRUE(get_session(stub(), s.name(), &after).ok());
  EXPECT_FALSE(decision(after, "layers")->applies());
  EXPECT_FALSE(decision(after, "shift")->applies());
}

}  // namespace
}  // namespace strata::test
