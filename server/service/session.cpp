#include "service/session.h"

#include <algorithm>
#include <cstdio>
#include <thread>
#include <glm/glm.hpp>

#include "include/frame_data.h"
#include "options/option_proto.h"
#include "scene/shutter.h"
#include "service/input_checks.h"
#include "service/scene_analysis.h"

namespace strata::service {
namespace {

double ms_between(Session::Clock::time_point a, Session::Clock::time_point b) {
  return std::chrono::duration<double, std::milli>(b - a).count();
}

std::string size_text(uint32_t w, uint32_t h) { return std::to_string(w) + "x" + std::to_string(h); }

std::string seconds_text(double s) {
  char text[32];
  std::snprintf(text, sizeof text, "%.1f s", s);
  return text;
}

// The method that renders a progressive start's frames until the session's own is compiled: its
// pipelines compile in about a second on lavapipe.
constexpr const char* k_stand_in = "pt";
// While the method compiles, the stand-in's frames are paced: after a frame that took r, the next
// starts no sooner than k_stand_in_idle x r later, so that rendering them takes about a quarter of
// the machine and the compile (which the method's first frame waits for) the rest. Unpaced, a
// 256x256 carousel session's pt frames took about half of a 2-core machine and the method's first
// frame came 42 s after the start instead of within 30 s (docs/BENCHMARKS.md, "Live viewer and
// first frames"). At most k_stand_in_idle_max later, so that a frame that included pt's own
// compile (the first) does not hold up the next for long.
constexpr double k_stand_in_idle = 3.0;
constexpr std::chrono::seconds k_stand_in_idle_max{2};

void set_time(google::protobuf::Timestamp* t, std::chrono::system_clock::time_point tp) {
  const auto ns = std::chrono::duration_cast<std::chrono::nanoseconds>(tp.time_since_epoch()).count();
  t->set_seconds(ns / 1'000'000'000);
  t->set_nanos(int32_t(ns % 1'000'000'000));
}

}  // namespace

Session::Session(std::string name, std::shared_ptr<const scene::Scene> scene, SessionSpec spec, const gpu::Context& ctx,
                 ServiceMetrics& metrics, WarmUp* progressive)
    : name_(std::move(name)),
      scene_(std::move(scene)),
      ctx_(ctx),
      metrics_(metrics),
      analysis_(analyze_scene(*scene_)),
      created_steady_(Clock::now()),
      created_(std::chrono::system_clock::now()),
      progressive_(progressive),
      spec_(std::move(spec)) {
  settings_ = render_settings(spec_);
  {
    std::lock_guard lock(mu_);
    redecide_locked();
  }
  frame_state_ = scene_->frame_state(0);
  idle_since_ = created_steady_;
  std::lock_guard lock(render_mu_);
  // `method auto` renders its first frames with its calibration's own runs.
  if (spec_.auto_method) return;
  std::vector<gpu::PipelineInfo> pipelines;
  if (progressive_ && settings_.method != k_stand_in && !progressive_->compiled(*scene_, settings_, &pipelines)) {
    // The stand-in first: a pipeline both share is then not waited for behind the compile.
    render::RenderSettings stand_in = settings_;
    stand_in.method = k_stand_in;
    stand_in_ = std::make_unique<render::Renderer>(ctx_, *scene_, stand_in);
    submit_compile_locked();
    std::printf("stratad: %s: the pipelines of %s compile in the background; %s renders its frames until then\n",
                name_.c_str(), settings_.method.c_str(), k_stand_in);
    std::fflush(stdout);
    return;
  }
  // Compiled before: created on every core at once, the renderer below finds them.
  if (!pipelines.empty()) progressive_->create(ctx_, pipelines, name_);
  create_renderer_locked();
}

Session::~Session() = default;

void Session::create_renderer_locked() {
  auto r = std::make_unique<render::Renderer>(ctx_, *scene_, settings_);
  auto memory = r->memory_bytes();
  renderer_ = std::move(r);
  std::lock_guard lock(mu_);
  memory_ = std::move(memory);
  released_ = false;
}

void Session::submit_compile_locked() {
  compile_ = progressive_->compile(scene_, settings_, name_);
}

bool Session::compiling_locked(uint64_t index, std::string& reason) {
  if (!compile_) return false;
  if (!compile_->first_frame_ready()) return true;
  const bool staged = !compile_->done();  // the history passes' pipelines still compile
  if (stand_in_ || !renderer_) {
    stand_in_.reset();
    const double s = staged ? compile_->first_frame_seconds() : compile_->seconds();
    const size_t n = compile_->pipelines() - (staged ? compile_->history_pipelines() : 0);
    reason += (reason.empty() ? "" : "; ") + settings_.method + "'s pipelines are compiled (" + std::to_string(n) + " in " +
              seconds_text(s) + "): it renders from this frame on, its history starting here" +
              (staged ? std::string(", its history passes held until theirs are compiled") : std::string());
    std::printf("stratad: %s: %s renders from frame %llu on (%zu pipelines compiled in %s%s)\n", name_.c_str(), settings_.method.c_str(),
                static_cast<unsigned long long>(index), n, seconds_text(s).c_str(), staged ? "; its history passes held" : "");
    std::fflush(stdout);
  }
  if (staged) {
    history_held_ = true;
    return false;
  }
  if (history_held_) {
    history_held_ = false;
    std::printf("stratad: %s: the history passes of %s are compiled (%zu pipelines in %s since the session began): its frames reuse history from frame %llu on\n",
                name_.c_str(), settings_.method.c_str(), compile_->history_pipelines(), seconds_text(compile_->seconds()).c_str(),
                static_cast<unsigned long long>(index));
    std::fflush(stdout);
  }
  compile_.reset();
  return false;
}

void Session::release_gpu() {
  std::lock_guard rl(render_mu_);
  std::lock_guard lock(mu_);
  if (attached_) return;  // a new stream came first: its frames use the GPU state
  renderer_.reset();
  stand_in_.reset();
  calibration_.reset();  // `method auto` calibrates again from the next frame
  memory_.clear();
  released_ = true;
}

uint64_t Session::device_bytes() const {
  std::lock_guard lock(mu_);
  uint64_t n = 0;
  for (const auto& [group, bytes] : memory_) n += bytes;
  return n;
}

bool Session::attach(const std::shared_ptr<AttachedStream>& stream) {
  std::lock_guard lock(mu_);
  if (attached_) return false;
  attached_ = true;
  stream_ = stream;
  return true;
}

bool Session::detach(const AttachedStream* stream) {
  std::lock_guard lock(mu_);
  auto current = stream_.lock();
  if (!attached_ || (current && current.get() != stream)) return false;
  attached_ = false;
  stream_.reset();
  idle_since_ = Clock::now();
  return true;
}

std::shared_ptr<AttachedStream> Session::stream() const {
  std::lock_guard lock(mu_);
  return stream_.lock();
}

void Session::note_input(uint64_t sequence) {
  std::lock_guard lock(mu_);
  last_input_ = sequence;
}

void Session::note_dropped(uint64_t frames) {
  std::lock_guard lock(mu_);
  frames_dropped_ += frames;
}

void Session::touch() {
  std::lock_guard lock(mu_);
  idle_since_ = Clock::now();
}

std::optional<Session::Clock::time_point> Session::idle_since() const {
  std::lock_guard lock(mu_);
  if (attached_) return std::nullopt;
  return idle_since_;
}

void Session::apply_locked(const PendingInput& input, std::string& reset_reason, std::vector<v1::Decision>& option_changes) {
  render::RenderSettings next = settings_;
  v1::RenderOptions before, options;
  bool radius_requested = false;
  {
    std::lock_guard lock(mu_);
    before = spec_.options;
    radius_requested = spec_.requested.has_spatial_radius();
  }
  options = before;
  options.MergeFrom(input.options);
  normalize(options);
  if (input.resolution) std::tie(next.width, next.height) = *input.resolution;
  // A radius never requested follows the image height (render::RestirOptions::default_spatial_radius).
  if (!radius_requested && !input.options.has_spatial_radius())
    options.set_spatial_radius(render::RestirOptions::default_spatial_radius(next.height));
  next.spp = options.spp();
  next.max_depth = options.max_depth();
  next.restir = restir_options(options);

  // `method auto` calibrates again where what it measured changes: the resolution, or the light.
  std::string recalibrate;
  if (spec_.auto_method) {
    for (const auto& [id, m] : input.transforms)
      if (instance_emits(*scene_, id) && m != frame_state_.transforms.at(id)) {
        recalibrate = "instance " + std::to_string(id) + ", which emits light, moved";
        break;
      }
    for (const auto& [id, m] : input.lights)
      if (recalibrate.empty() && m != frame_state_.lights.at(id)) recalibrate = "light " + std::to_string(id) + " moved";
  }

  // Every option the input changed (options/option_table.h, OnChange): one that applies to the
  // method re-creates the GPU state or takes effect in place; one that does not is kept and said so.
  std::string changes;
  auto add = [&](const std::string& c) { changes += (changes.empty() ? "" : "; ") + c; };
  if (next.width != settings_.width || next.height != settings_.height)
    add("resolution changed from " + size_text(settings_.width, settings_.height) + " to " + size_text(next.width, next.height));
  const bool resized = !changes.empty();
  for (const OptionChange& c : service::option_changes(method(), before, options)) {
    const std::string what = std::string(c.option->name) + " changed from " + c.from + " to " + c.to;
    v1::Decision d;
    d.set_name(c.option->name);
    d.set_requested(options::has_value(input.options, *c.option) ? c.to : "");  // empty: it followed the image height
    d.set_value(c.to);
    d.set_applies(c.applies);
    if (!c.applies) {
      d.set_reason(what + ": " + options::not_applying_reason(*c.option, method()));
    } else if (c.option->on_change == options::OnChange::in_place) {
      d.set_reason(what + ": takes effect from this frame on (the GPU state is kept)");
    } else if (resized && c.option->default_from == options::DefaultFrom::image_height && !input.options.has_spatial_radius()) {
      d.set_reason(what + ": follows the image height (the resolution change re-creates the GPU state)");
    } else {
      d.set_reason(what + ": the GPU state is re-created with it from this frame on");
      add(what);
    }
    option_changes.push_back(std::move(d));
  }
  settings_.restir = next.restir;  // options that do not apply change nothing on the device
  if (!changes.empty()) {
    settings_ = next;
    renderer_.reset();
    stand_in_.reset();
    if (compile_) submit_compile_locked();  // the pipelines of the new settings (the variants may differ)
    reset_reason += (reset_reason.empty() ? "" : "; ") + changes + " (the GPU state is re-created)";
    if (spec_.auto_method && recalibrate.empty()) {
      if (resized) recalibrate = "the resolution changed";
      else if (calibration_) recalibrate = "the options changed while it calibrated";
    }
  }

  const bool options_changed = input.options.ByteSizeLong() > 0 || !input.encodings.empty();
  {
    std::lock_guard lock(mu_);
    spec_.options = options;
    spec_.requested.MergeFrom(input.options);
    spec_.width = settings_.width;
    spec_.height = settings_.height;
    if (!input.encodings.empty()) spec_.encodings = input.encodings;
    if (options_changed) redecide_locked();
  }
  if (!recalibrate.empty()) {
    recalibrate_locked(recalibrate);
    reset_reason += (reset_reason.empty() ? "" : "; ") + std::string("method auto calibrates again: ") + recalibrate;
  }

  if (input.animation_frame) frame_state_ = scene_->frame_state(*input.animation_frame);
  if (input.camera) frame_state_.camera = *input.camera;
  for (const auto& [id, m] : input.transforms) frame_state_.transforms.at(id) = m;
  for (const auto& [id, level] : input.lods) frame_state_.lods.at(id) = level;
  for (const auto& [id, m] : input.lights) frame_state_.lights.at(id) = m;
  for (const auto& [id, pose] : input.joints)
    for (const auto& [j, m] : pose) frame_state_.joints.at(id).at(j) = m;
  for (const auto& [id, w] : input.morph_weights) frame_state_.morph_weights.at(id) = w;
}

RenderedFrame Session::render(PendingInput input) {
  std::lock_guard rl(render_mu_);
  const auto start = Clock::now();
  std::string reason;
  std::vector<v1::Decision> option_changes;
  uint64_t index = 0;
  {
    std::lock_guard lock(mu_);
    index = frames_rendered_;
    if (frames_rendered_ == 0) reason = "first frame of the session";
    else if (released_) reason = "the GPU state was released when the previous stream ended and is re-created";
  }
  apply_locked(input, reason, option_changes);
  bool calibrating = false;
  {
    std::lock_guard lock(mu_);
    calibrating = spec_.auto_method && !(auto_choice_ && auto_choice_->method);
  }
  const bool compiling = !calibrating && compiling_locked(index, reason);
  if (compiling && !stand_in_) {
    render::RenderSettings stand_in = settings_;
    stand_in.method = k_stand_in;
    stand_in_ = std::make_unique<render::Renderer>(ctx_, *scene_, stand_in);
  }
  if (!calibrating && !compiling && !renderer_) create_renderer_locked();
  if (!calibrating && !compiling) renderer_->hold_history(history_held_);
  // Motion blur (RS-main 4.4): the shutter opens on the way from the camera of the frame rendered
  // before; the session's first frame has none and is an instant.
  frame_state_.camera_open = last_camera_ ? scene::shutter_open_camera(*last_camera_, frame_state_.camera) : std::nullopt;

  if (compiling && stand_in_resume_ > Clock::now()) std::this_thread::sleep_until(stand_in_resume_);
  const auto render_start = Clock::now();
  RenderedFrame f;
  f.result = calibrating  ? render_calibrating_locked(index, option_changes)
             : compiling ? stand_in_->render(frame_state_, uint32_t(index))
                         : renderer_->render(frame_state_, uint32_t(index));
  if (compiling) {
    const auto rendered = Clock::now();
    const auto idle = std::chrono::duration_cast<Clock::duration>((rendered - render_start) * k_stand_in_idle);
    stand_in_resume_ = rendered + std::min<Clock::duration>(idle, k_stand_in_idle_max);
    const size_t n = compile_->pipelines();
    f.result.stats.passes.insert(
        f.result.stats.passes.begin(),
        {settings_.method, false,
         settings_.method + " compiling: rendered by " + k_stand_in + " (" + (n ? std::to_string(n) + " pipelines" : std::string("its pipelines")) +
             " compiling in the background for " + seconds_text(compile_->seconds()) + "; " + settings_.method +
             " renders from the frame after those of a frame without history are compiled, its history starting there; "
             "these frames are paced to leave most of the machine to the compile)"});
  }
  last_camera_ = frame_state_.camera;
  const auto done = Clock::now();
  f.frame_index = index;
  f.input_sequence = input.sequence;
  f.coalesced = input.coalesced;
  f.history_reset = !reason.empty();
  f.history_reset_reason = reason;
  f.option_changes = std::move(option_changes);
  f.queued_ms = ms_between(input.received, start);
  f.render_ms = ms_between(start, done);
  {
    std::lock_guard lock(mu_);
    f.encodings = spec_.encodings;
    f.exposure = spec_.options.exposure();
    memory_ = f.result.stats.memory_bytes;
    last_passes_ = f.result.stats.passes;
    ++frames_rendered_;
    inputs_coalesced_ += input.coalesced;
  }
  // The domain map is read back only for frames that carry it (a few MB at 256 x 256 x 3 layers).
  if (std::find(f.encodings.begin(), f.encodings.end(), v1::IMAGE_ENCODING_DOMAIN_MAP) != f.encodings.end())
    f.result.domain_map = (compiling ? stand_in_ : renderer_)->domain_map();
  metrics_.frames_rendered.fetch_add(1);
  metrics_.inputs_coalesced.fetch_add(input.coalesced);
  f.held = GaugeHold(metrics_.buffered_frame_bytes, int64_t(f.result.image.rgba.size() * sizeof(float)));
  metrics_.frame_observers.notify({name_, scene_->name, compiling ? stand_in_->settings().method : settings_.method, f});
  return f;
}

void Session::recalibrate_locked(const std::string& why) {
  renderer_.reset();
  calibration_.reset();
  const render::MethodSpec& reuse = render::method_spec(k_auto_reuse);
  std::lock_guard lock(mu_);
  auto_choice_.reset();
  calibration_reason_ = why;
  spec_.method = &reuse;
  if (!spec_.requested.has_confidence_cap()) spec_.options.set_confidence_cap(reuse.confidence_cap);
  settings_.method = reuse.name;
  settings_.restir = restir_options(spec_.options);
  redecide_locked();
}

render::FrameResult Session::render_calibrating_locked(uint64_t index, std::vector<v1::Decision>& option_changes) {
  if (!calibration_) {
    std::optional<float> cap;
    {
      std::lock_guard lock(mu_);
      if (spec_.requested.has_confidence_cap()) cap = spec_.requested.confidence_cap();
      else spec_.options.set_confidence_cap(render::method_spec(k_auto_reuse).confidence_cap);
      auto_choice_.reset();  // what an interrupted calibration measured
      calibration_start_ = index;
      redecide_locked();
    }
    render::RenderSettings reuse = settings_;
    reuse.method = k_auto_reuse;
    calibration_ = std::make_unique<AutoCalibration>(ctx_, *scene_, reuse, cap, index);
  }
  render::FrameResult r = calibration_->render(frame_state_, uint32_t(index));
  if (!calibration_->done()) {
    // After its first frame the calibration has chosen restir-gather's cap: the options and the
    // decisions say it from then on.
    const AutoChoice& so_far = calibration_->choice();
    std::lock_guard lock(mu_);
    if (!auto_choice_) {
      auto_choice_ = so_far;
      if (so_far.cap_chosen) spec_.options.set_confidence_cap(so_far.confidence_cap);
      redecide_locked();
    }
    return r;
  }

  // The choice: its first run goes on as the session's renderer (restir-gather's history is kept).
  const AutoChoice choice = calibration_->choice();
  renderer_ = calibration_->take_chosen();
  calibration_.reset();
  std::lock_guard lock(mu_);
  auto_choice_ = choice;
  spec_.method = choice.method;
  if (choice.method->reuse && choice.cap_chosen) spec_.options.set_confidence_cap(choice.confidence_cap);
  settings_ = renderer_->settings();
  settings_.restir = restir_options(spec_.options);
  redecide_locked();
  for (const auto& d : decisions_)
    if (d.name() == "method") {
      v1::Decision change = d;
      change.set_reason(change.reason() + "; from frame " + std::to_string(index + 1) + " on, the GPU state of its first run "
                        "goes on (" + (choice.method->reuse ? "its history is kept" : "pt keeps no history") + ")");
      option_changes.push_back(std::move(change));
    }
  return r;
}

void Session::redecide_locked() {
  decisions_ = decide(*spec_.method, spec_.requested_method, spec_.requested, spec_.options, spec_.encodings, analysis_,
                      measured_layers(spec_.options, spec_.width, spec_.height));
  if (spec_.auto_method) describe_auto(decisions_, spec_.requested_method, auto_choice_, calibration_start_, calibration_reason_);
}

const std::optional<render::LayerCount>& Session::measured_layers(const v1::RenderOptions& options, uint32_t width,
                                                                  uint32_t height) {
  if (!spec_.method->layers || options.layers() != 0) {
    measured_layers_.reset();
  } else if (!measured_layers_ || measured_width_ != width || measured_height_ != height) {
    // 64 x 64 ray queries of the first frame (the renderer measures the same when it is created).
    measured_layers_ = render::measure_layers(ctx_, *scene_, scene_->frame_state(0), width, height);
    measured_width_ = width;
    measured_height_ = height;
  }
  return measured_layers_;
}

const render::MethodSpec& Session::method() const {
  std::lock_guard lock(mu_);
  return *spec_.method;
}

const render::MethodSpec& Session::checked_method() const {
  if (spec_.auto_method) return render::method_spec(k_auto_reuse);  // auto_method never changes
  return method();
}

v1::Session Session::describe(const ServiceConfig& config) const {
  v1::Session s;
  s.set_name(name_);
  s.set_scene(scene_->name);
  s.set_seed(settings_.seed);  // constant after construction
  *s.mutable_analysis() = analysis_;
  set_time(s.mutable_create_time(), created_);
  std::lock_guard lock(mu_);
  s.mutable_resolution()->set_width(spec_.width);
  s.mutable_resolution()->set_height(spec_.height);
  s.set_method(spec_.method->name);
  *s.mutable_options() = spec_.options;
  for (auto e : spec_.encodings) s.add_encodings(e);
  for (const auto& d : decisions_) *s.add_decisions() = d;
  for (const auto& p : last_passes_) {
    auto* out = s.add_passes();
    out->set_pass(p.pass);
    out->set_ran(p.ran);
    out->set_reason(p.reason);
  }
  uint64_t total = 0;
  for (const auto& [group, bytes] : memory_) {
    (*s.mutable_memory()->mutable_bytes_by_group())[group] = bytes;
    total += bytes;
  }
  s.mutable_memory()->set_total_bytes(total);
  s.set_state(attached_ ? v1::Session::STREAMING : v1::Session::IDLE);
  s.set_frames_rendered(frames_rendered_);
  s.set_frames_dropped(frames_dropped_);
  s.set_inputs_coalesced(inputs_coalesced_);
  s.set_last_input_sequence(last_input_);
  if (!attached_) {
    const auto left = idle_since_ + config.idle_timeout - Clock::now();
    set_time(s.mutable_expire_time(),
             std::chrono::system_clock::now() + std::chrono::duration_cast<std::chrono::system_clock::duration>(left));
  }
  s.set_max_frame_bytes(max_frame_bytes(uint64_t(spec_.width) * spec_.height));
  return s;
}

}  // namespace strata::service
