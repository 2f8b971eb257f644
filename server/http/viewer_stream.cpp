#include "http/viewer_stream.h"

#include <chrono>
#include <cmath>

#include "http/frame_jpeg.h"
#include "http/instance_pick.h"
#include "http/viewer_messages.h"
#include "http/viewer_options.h"
#include "http/viewer_overlay.h"
#include "render/method_table.h"
#include "scene/transform.h"
#include "service/errors.h"
#include "service/method_auto.h"
#include "service/options.h"
#include "service/scene_source.h"
#include "service/session_spec.h"

namespace strata::http {

using service::fail;
using service::fail_invalid;

ViewerStream::ViewerStream(service::ServiceCore& core, std::shared_ptr<const service::BearerToken> token,
                           std::shared_ptr<ViewerTransport> transport)
    : core_(core), token_(std::move(token)), transport_(std::move(transport)) {}

ViewerStream::~ViewerStream() {
  if (sender_.joinable()) sender_.join();  // on_closed joined it already unless start() ran alone
}

void ViewerStream::start() {
  core_.metrics.streams.fetch_add(1);
  counted_ = true;
  core_.streams.add(shared_from_this());
  sender_ = std::thread([this] { sender(); });
}

// ---- messages from the page ----------------------------------------------------------------------

void ViewerStream::refuse(int code, const std::string& message) {
  {
    std::lock_guard lock(mu_);
    if (!close_status_ || close_status_->ok()) close_status_ = grpc::Status(grpc::StatusCode::INVALID_ARGUMENT, message);
    close_immediate_ = true;
    refused_ = true;
    cv_.notify_all();
  }
  transport_->send_text(nlohmann::json{{"type", "error"}, {"code", code}, {"message", message}}.dump());
  transport_->close(code, message);
}

bool ViewerStream::closing() const {
  std::lock_guard lock(mu_);
  return refused_;
}

void ViewerStream::on_text(std::string_view text) {
  if (text.size() > k_max_viewer_message)
    return refuse(1009, "a message of " + std::to_string(text.size()) + " bytes exceeds the limit of " +
                            std::to_string(k_max_viewer_message) + " bytes");
  const auto msg = nlohmann::json::parse(text, nullptr, false);
  if (msg.is_discarded() || !msg.is_object()) return refuse(4400, "a message is not a JSON object");
  const grpc::Status st = service::guarded([&] { handle(msg); });
  if (!st.ok()) refuse(close_code(st.error_code()), st.error_message());
}

void ViewerStream::handle(const nlohmann::json& msg) {
  const std::string type = type_of(msg);
  bool greeted = false;
  {
    std::lock_guard lock(mu_);
    greeted = greeted_;
  }
  if (!greeted && type != "hello") fail_invalid("the first message must be hello (got " + type + ")");
  if (type == "hello") hello(msg);
  else if (type == "create") create(msg);
  else if (type == "attach") {
    if (!msg.contains("session") || !msg["session"].is_string()) fail_invalid("attach.session is required (sessions/{session})");
    attach(msg["session"].get<std::string>(), false);
  } else if (type == "input") input(msg);
  else if (type == "pick") pick(msg);
  else if (type == "ack") ack(msg);
  else if (type == "overlay") overlay(msg);
  else if (type == "ping") transport_->send_text(R"({"type":"pong"})");
  else fail_invalid("type = '" + type + "' is not one of hello, create, attach, input, pick, ack, overlay, ping");
}

void ViewerStream::hello(const nlohmann::json& msg) {
  {
    std::lock_guard lock(mu_);
    if (greeted_) fail_invalid("hello was sent already; send it once, first");
  }
  if (token_) {
    if (!msg.contains("token") || !msg["token"].is_string())
      fail(grpc::StatusCode::UNAUTHENTICATED, "this daemon requires a token (--auth-token-file): send it as hello.token");
    const std::string bearer = "Bearer " + msg["token"].get<std::string>();
    const std::multimap<grpc::string_ref, grpc::string_ref> metadata = {{"authorization", bearer}};
    const grpc::Status st = token_->check(metadata);
    if (!st.ok()) fail(st.error_code(), st.error_message());
  }
  if (core_.draining.load()) fail(grpc::StatusCode::UNAVAILABLE, "stratad is draining (shutting down): no new sessions");
  nlohmann::json scenes = nlohmann::json::array();
  for (const auto& e : service::list_scenes(core_.config)) scenes.push_back(proto_json(e));
  const auto& l = core_.config.limits;
  nlohmann::json reply = {{"type", "hello"},
                          {"device", core_.ctx.device_name()},
                          {"methods", service::session_methods()},
                          {"default_method", service::k_auto_method},
                          {"domain_map_methods", domain_map_methods()},
                          {"scenes", scenes},
                          {"options", viewer_options_json()},
                          {"limits", {{"max_sessions", l.max_sessions}, {"max_dimension", l.max_dimension}, {"max_pixels", l.max_pixels}}}};
  {
    std::lock_guard lock(mu_);
    greeted_ = true;
  }
  transport_->send_text(reply.dump());
}

void ViewerStream::create(const nlohmann::json& msg) {
  if (core_.draining.load()) fail(grpc::StatusCode::UNAVAILABLE, "stratad is draining (shutting down): no new sessions");
  v1::CreateSessionRequest req;
  proto_from_json(msg.value("request", nlohmann::json()), &req, "create.request");
  end_session();  // a viewer shows one session: a new one (another method, say) replaces it
  const service::SessionSpec spec = service::check_create_session(req, core_.config.limits);
  auto session = core_.registry.create(req.session_id(), "create.request.session_id", [&](const std::string& name) {
    auto scene = service::load_scene_source(req.scene(), core_.config);
    return std::make_shared<service::Session>(name, std::move(scene), spec, core_.ctx, core_.metrics, core_.progressive_start());
  });
  try {
    attach(session->name(), true);
  } catch (...) {
    core_.registry.remove(session->name(), "could not be attached to its viewer");
    throw;
  }
}

void ViewerStream::attach(const std::string& name, bool owned) {
  if (!owned) end_session();
  auto s = core_.registry.get(name, "session");
  if (!s->attach(shared_from_this()))
    fail(grpc::StatusCode::ABORTED, "session '" + s->name() +
                                        "' already has a stream attached (another viewer tab or a gRPC stream); one stream per session at a time");
  std::string message;
  {
    std::lock_guard lock(mu_);
    session_ = s;
    owned_ = owned;
    state_ = s->scene().frame_state(0);
    camera_ = state_.camera;
    last_sequence_ = 0;
    unacknowledged_.reset();
    const auto d = s->describe(core_.config);
    base_encodings_.clear();
    for (const int e : d.encodings()) base_encodings_.push_back(v1::ImageEncoding(e));
    domain_map_overlay_ = overlay_changed_ = false;
    message = session_message_locked(s);
  }
  transport_->send_text(message);  // not under mu_: a slow reader must not hold up the frame scheduler
}

std::string ViewerStream::session_message_locked(const std::shared_ptr<service::Session>& s) {
  nlohmann::json instances = nlohmann::json::array();
  const auto& scene = s->scene();
  for (uint32_t i = 0; i < scene.instances.size(); ++i) {
    auto j = transform_json(state_.transforms[i]);
    j["id"] = i;
    j["name"] = scene.instances[i].name;
    j["lod_levels"] = scene.instances[i].lod_meshes.size();
    j["lod"] = state_.lods[i];
    instances.push_back(std::move(j));
  }
  return nlohmann::json{{"type", "session"},
                        {"session", proto_json(s->describe(core_.config))},
                        {"owned", owned_},
                        {"camera", camera_json(state_.camera)},
                        {"instances", std::move(instances)}}
      .dump();
}

void ViewerStream::input(const nlohmann::json& msg) {
  std::shared_ptr<service::Session> s;
  uint64_t last = 0;
  {
    std::lock_guard lock(mu_);
    s = session_;
    last = last_sequence_;
  }
  if (!s) fail(grpc::StatusCode::FAILED_PRECONDITION, "input before create or attach: the viewer has no session yet");
  v1::FrameInput in;
  proto_from_json(msg.value("input", nlohmann::json()), &in, "input.input");
  if (!in.session().empty() && in.session() != s->name())
    fail_invalid("input.session = '" + in.session() + "' differs from this viewer's session '" + s->name() + "'; leave it empty");
  if (in.sequence() <= last)
    fail_invalid(last == 0 ? "input.sequence = " + std::to_string(in.sequence()) + ": sequences start at 1"
                           : "input.sequence = " + std::to_string(in.sequence()) + " is not greater than the previous sequence " +
                                 std::to_string(last));
  if (!in.encodings().empty()) fail_invalid("input.encodings: the viewer's frames are JPEG; leave encodings empty");
  service::PendingInput p = service::parse_frame_input(in, s->scene(), core_.config.limits);
  service::check_method_options(s->checked_method(), p.options, "input.options", s->auto_method());
  s->note_input(in.sequence());
  bool enqueue = false;
  {
    std::lock_guard lock(mu_);
    if (s != session_) return;  // replaced meanwhile
    last_sequence_ = in.sequence();
    if (p.animation_frame) state_ = s->scene().frame_state(*p.animation_frame);
    if (p.camera) state_.camera = *p.camera;
    for (const auto& [id, m] : p.transforms) state_.transforms[id] = m;
    for (const auto& [id, level] : p.lods) state_.lods[id] = level;
    camera_ = state_.camera;
    if (!accept_inputs_) return;  // draining: only inputs that arrived before are rendered
    pending_options_ = pending_options_ || in.has_options();
    if (pending_) pending_->merge_newer(std::move(p));
    else pending_ = std::move(p);
    if (!queued_ && !rendering_ && !close_immediate_) enqueue = queued_ = true;
  }
  if (enqueue) core_.scheduler.enqueue(shared_from_this());
}

void ViewerStream::pick(const nlohmann::json& msg) {
  const double x = number(msg, "x", "pick"), y = number(msg, "y", "pick");
  if (!std::isfinite(x) || !std::isfinite(y) || x < 0.0 || x > 1.0 || y < 0.0 || y > 1.0)
    fail_invalid("pick.x, pick.y = " + std::to_string(x) + ", " + std::to_string(y) + " are outside [0, 1] (image fractions)");
  std::shared_ptr<service::Session> s;
  scene::FrameState state;
  float aspect = 1.0f;
  {
    std::lock_guard lock(mu_);
    s = session_;
    state = state_;
  }
  if (!s) fail(grpc::StatusCode::FAILED_PRECONDITION, "pick before create or attach: the viewer has no session yet");
  const auto d = s->describe(core_.config);
  aspect = float(d.resolution().width()) / float(std::max(1u, d.resolution().height()));
  const auto hit = pick_instance(s->scene(), state, float(x), float(y), aspect);
  nlohmann::json reply = {{"type", "pick"}, {"x", x}, {"y", y}};
  if (hit) {
    reply["instance"] = hit->instance;
    reply["name"] = s->scene().instances[hit->instance].name;
    reply["distance"] = hit->distance;
    reply["point"] = vec3_json(hit->point);
    reply["transform"] = transform_json(state.transforms[hit->instance]);
    reply["lod"] = state.lods[hit->instance];
    reply["lod_levels"] = s->scene().instances[hit->instance].lod_meshes.size();
  } else {
    reply["instance"] = nullptr;
  }
  transport_->send_text(reply.dump());
}

void ViewerStream::ack(const nlohmann::json& msg) {
  if (!msg.contains("frame") || !msg["frame"].is_number_unsigned()) fail_invalid("ack.frame is required (the frame index drawn)");
  const uint64_t frame = msg["frame"].get<uint64_t>();
  std::lock_guard lock(mu_);
  if (!unacknowledged_ || *unacknowledged_ != frame)
    fail_invalid("ack.frame = " + std::to_string(frame) + " is not the frame awaiting acknowledgement (" +
                 (unacknowledged_ ? std::to_string(*unacknowledged_) : std::string("none")) + ")");
  unacknowledged_.reset();
  cv_.notify_all();
}

void ViewerStream::overlay(const nlohmann::json& msg) {
  if (!msg.contains("domain_map") || !msg["domain_map"].is_boolean())
    fail_invalid("overlay.domain_map is required (true or false)");
  const bool on = msg["domain_map"].get<bool>();
  std::lock_guard lock(mu_);
  if (!session_) fail(grpc::StatusCode::FAILED_PRECONDITION, "overlay before create or attach: the viewer has no session yet");
  if (on && !session_->method().layers)
    fail(grpc::StatusCode::FAILED_PRECONDITION, "overlay.domain_map: the domain map needs a method with pixel layers (" +
                                                    nlohmann::json(domain_map_methods()).dump() + "); this session renders " +
                                                    session_->method().name);
  overlay_changed_ = overlay_changed_ || on != domain_map_overlay_;
  domain_map_overlay_ = on;
}

// ---- rendering and sending -----------------------------------------------------------------------

void ViewerStream::render_pending() {
  std::optional<service::PendingInput> input;
  std::shared_ptr<service::Session> s;
  scene::Camera camera;
  bool options = false;
  {
    std::lock_guard lock(mu_);
    queued_ = false;
    if (!pending_ || !session_ || close_immediate_ || closed_) return;
    input = std::move(pending_);
    pending_.reset();
    options = pending_options_;
    pending_options_ = false;
    if (overlay_changed_) {  // the session reads the domain map back only for frames whose encodings carry it
      input->encodings = base_encodings_;
      if (domain_map_overlay_ && std::find(input->encodings.begin(), input->encodings.end(), v1::IMAGE_ENCODING_DOMAIN_MAP) ==
                                     input->encodings.end())
        input->encodings.push_back(v1::IMAGE_ENCODING_DOMAIN_MAP);
      if (input->encodings.empty()) input->encodings.push_back(v1::IMAGE_ENCODING_EXR_HALF);
      overlay_changed_ = false;
      options = true;
    }
    rendering_ = true;
    s = session_;
    camera = camera_.value_or(state_.camera);
  }
  std::optional<service::RenderedFrame> frame;
  grpc::Status error;
  try {
    frame = s->render(std::move(*input));
  } catch (const std::exception& e) {
    error = service::status_from_exception(e);
  }
  bool enqueue = false;
  {
    std::lock_guard lock(mu_);
    rendering_ = false;
    if (!frame) {
      if (!close_status_ || close_status_->ok()) close_status_ = error;
      close_immediate_ = true;
    } else if (s == session_ && !close_immediate_) {
      if (slot_) {  // latest frame wins: the one waiting is dropped; what the page must still learn carries over
        ++dropped_since_sent_;
        ++dropped_total_;
        s->note_dropped(1);
        core_.metrics.frames_dropped.fetch_add(1);
        frame->coalesced += slot_->rendered.coalesced;
        if (slot_->rendered.history_reset) {
          frame->history_reset_reason =
              slot_->rendered.history_reset_reason + (frame->history_reset ? "; " + frame->history_reset_reason : "");
          frame->history_reset = true;
        }
        options = options || slot_->options_changed;
      }
      slot_ = Frame{std::move(*frame), camera, options};
    }
    if (pending_ && !queued_ && !close_immediate_) enqueue = queued_ = true;
    cv_.notify_all();
  }
  if (enqueue) core_.scheduler.enqueue(shared_from_this());
}

std::string ViewerStream::frame_message(Frame& f) {
  const auto& r = f.rendered;
  const auto start = std::chrono::steady_clock::now();
  const auto jpeg = encode_jpeg_preview(r.result.image, r.exposure);
  const auto overlay = domain_map_overlay(r.result.domain_map);
  const double encode_ms = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
  nlohmann::json passes = nlohmann::json::object();
  for (const auto& p : r.result.stats.pass_ms) passes[p.pass] = passes.value(p.pass, 0.0) + p.ms;
  nlohmann::json decisions = nlohmann::json::array();
  for (const auto& p : r.result.stats.passes) decisions.push_back({{"pass", p.pass}, {"ran", p.ran}, {"reason", p.reason}});
  nlohmann::json h = {{"frame", r.frame_index},
                      {"input_sequence", r.input_sequence},
                      {"width", r.result.image.width},
                      {"height", r.result.image.height},
                      {"gpu_ms", r.result.stats.gpu_ms_total},
                      {"pass_ms", passes},
                      {"passes", decisions},
                      {"queued_ms", r.queued_ms},
                      {"render_ms", r.render_ms},
                      {"encode_ms", encode_ms},
                      {"jpeg_bytes", jpeg.size()},
                      {"dropped", r.dropped_before},
                      {"coalesced", r.coalesced},
                      {"history_reset", r.history_reset},
                      {"history_reset_reason", r.history_reset_reason},
                      {"camera", camera_json(f.camera)}};
  if (overlay) h["overlay"] = overlay->header;
  {
    std::lock_guard lock(mu_);
    h["dropped_total"] = dropped_total_;
    if (f.options_changed && session_) h["session"] = proto_json(session_->describe(core_.config));
  }
  const std::string header = h.dump(-1, ' ', false, nlohmann::json::error_handler_t::replace);
  std::string out(4, '\0');
  const uint32_t n = uint32_t(header.size());
  for (int i = 0; i < 4; ++i) out[i] = char((n >> (8 * i)) & 0xff);
  out += header;
  out.append(reinterpret_cast<const char*>(jpeg.data()), jpeg.size());
  if (overlay) out.append(reinterpret_cast<const char*>(overlay->png.data()), overlay->png.size());
  return out;
}

void ViewerStream::sender() {
  std::unique_lock lock(mu_);
  for (;;) {
    cv_.wait(lock, [&] {
      const bool nothing_left = !pending_ && !rendering_ && !slot_;
      return closed_ || (close_status_ && (close_immediate_ || nothing_left)) || (slot_ && !unacknowledged_);
    });
    if (closed_) return;
    if (slot_ && !unacknowledged_ && !close_immediate_) {
      Frame f = std::move(*slot_);
      slot_.reset();
      f.rendered.dropped_before = dropped_since_sent_;
      dropped_since_sent_ = 0;
      unacknowledged_ = f.rendered.frame_index;
      lock.unlock();
      std::string message;
      const grpc::Status st = service::guarded([&] { message = frame_message(f); });
      f.rendered.held.release();
      if (st.ok()) transport_->send_binary(message);
      lock.lock();
      if (!st.ok()) {
        close_status_ = st;
        close_immediate_ = true;
      }
      continue;
    }
    // Ending: the error (if any) and the close frame are the last things sent (refuse() sent them already).
    const grpc::Status st = *close_status_;
    const bool sent = refused_;
    refused_ = true;
    close_immediate_ = true;
    lock.unlock();
    if (sent) {
      lock.lock();
      cv_.wait(lock, [&] { return closed_; });
      return;
    }
    if (!st.ok())
      transport_->send_text(nlohmann::json{{"type", "error"}, {"code", close_code(st.error_code())}, {"message", st.error_message()}}.dump());
    transport_->close(close_code(st.error_code()), st.ok() ? "the session ended" : st.error_message());
    lock.lock();
    cv_.wait(lock, [&] { return closed_; });
    return;
  }
}

// ---- ending --------------------------------------------------------------------------------------

void ViewerStream::request_close(grpc::Status status, bool immediate) {
  std::lock_guard lock(mu_);
  if (!close_status_ || (immediate && !close_immediate_)) {
    if (!close_status_ || close_status_->ok() || immediate) close_status_ = std::move(status);
    close_immediate_ = close_immediate_ || immediate;
  }
  cv_.notify_all();
}

void ViewerStream::end(grpc::Status status) { request_close(std::move(status), true); }

void ViewerStream::drain(grpc::Status status) {
  {
    std::lock_guard lock(mu_);
    accept_inputs_ = false;
  }
  request_close(std::move(status), false);
}

void ViewerStream::enforce_end_deadline(std::chrono::steady_clock::time_point) {
  // A viewer that stops acknowledging frames while the daemon drains: the frame waiting is not sent.
  std::lock_guard lock(mu_);
  if (close_status_ && !close_immediate_ && unacknowledged_ && !rendering_ && !pending_) {
    close_immediate_ = true;
    cv_.notify_all();
  }
}

void ViewerStream::end_session() {
  std::shared_ptr<service::Session> s;
  bool owned = false;
  {
    std::lock_guard lock(mu_);
    s = std::move(session_);
    session_.reset();
    owned = owned_;
    owned_ = false;
    pending_.reset();
    pending_options_ = false;
    slot_.reset();
    unacknowledged_.reset();
    cv_.notify_all();
  }
  if (!s) return;
  s->detach(this);
  if (owned) core_.registry.remove(s->name(), "was closed by its viewer");
  else core_.pool.post([s] { s->release_gpu(); });
}

void ViewerStream::on_closed() {
  {
    std::lock_guard lock(mu_);
    closed_ = true;
    cv_.notify_all();
  }
  if (sender_.joinable()) sender_.join();
  end_session();
  if (counted_) core_.metrics.streams.fetch_sub(1);
  counted_ = false;
}

}  // namespace strata::http
