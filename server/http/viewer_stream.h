#pragma once
// One viewer socket (/view/ws): the page's messages in, frames out, with a session of the service
// core attached exactly as a gRPC Stream attaches one (service/stream_reactor.h): the same checks of
// every input (parse_frame_input, check_method_options), the same limits and counters, one stream
// per session, latest input wins (inputs merge while a frame renders) and latest frame wins (a frame
// rendered while the previous one is still unacknowledged replaces the one waiting, and the drop is
// counted). The page acknowledges each frame it has drawn; the next frame goes out only then, so a
// slow viewer gets the newest frame, never a queue: the server holds at most one pending input, one
// frame waiting and one being encoded or sent.
//
// Messages from the page are JSON text; the first must be `hello` (with the token when the daemon
// has one). Frames are binary: a 4-byte little-endian header length, the header (JSON: frame index,
// input sequence, pass times, server timings, drops), then the JPEG, then, when the header has
// `overlay`, the overlay's PNG (http/viewer_overlay.h: the domain map, which the page turns on with
// an `overlay` message for a method with pixel layers). Any bad message ends the socket
// with an `error` message naming what was wrong and a close frame whose code says the kind (4000 +
// the HTTP status that fits: 4400 invalid, 4401 token, 4404 not found, 4409 session taken, 4429 over
// max_sessions, 4503 draining) and whose reason is the message's start. Closing the socket ends the
// session the viewer created (or detaches from one it attached to) and frees its device memory.
#include <condition_variable>
#include <cstdint>
#include <memory>
#include <mutex>
#include <optional>
#include <string>
#include <string_view>
#include <thread>

#include <nlohmann/json.hpp>

#include "http/viewer_messages.h"
#include "scene/scene.h"
#include "service/auth_token.h"
#include "service/frame_input.h"
#include "service/service_core.h"
#include "service/session.h"

namespace strata::http {

// Where a viewer's messages go (the civetweb connection; service/viewer_socket.cpp). Thread-safe;
// after close() every send returns false.
class ViewerTransport {
 public:
  virtual ~ViewerTransport() = default;
  virtual bool send_text(const std::string& text) = 0;
  virtual bool send_binary(const std::string& bytes) = 0;
  // Sends a close frame with `code` and `reason` (cut to the 123 bytes a close frame holds).
  virtual void close(int code, const std::string& reason) = 0;
};

constexpr size_t k_max_viewer_message = 1 << 20;  // bytes of one message from the page

// The close code for a status: 1000 for OK, else 4000 + the fitting HTTP status.


class ViewerStream final : public service::AttachedStream,
                           public service::ScheduledStream,
                           public std::enable_shared_from_this<ViewerStream> {
 public:
  // `token`: the daemon's bearer token, nullptr when it has none.
  ViewerStream(service::ServiceCore& core, std::shared_ptr<const service::BearerToken> token,
               std::shared_ptr<ViewerTransport> transport);
  ~ViewerStream() override;
  // Counts the stream (ServiceMetrics::streams) and starts the thread that sends frames.
  void start();

  // One text message. A bad one is refused (see refuse).
  void on_text(std::string_view text);
  // Sends an error message naming the problem and a close frame with `code`; the page's answering
  // close frame then ends the connection.
  void refuse(int code, const std::string& message);
  // A close frame was sent: whatever else arrives ends the connection at once.
  bool closing() const;
  // The socket is gone: the sender stops, the session is ended (or detached) and its GPU state freed.
  void on_closed();

  void end(grpc::Status status) override;
  void drain(grpc::Status status) override;
  void enforce_end_deadline(std::chrono::steady_clock::time_point now) override;
  void render_pending() override;

 private:
  struct Frame {
    service::RenderedFrame rendered;
    scene::Camera camera;          // of the input it rendered
    bool options_changed = false;  // the session's description (decisions) goes with it
  };

  void handle(const nlohmann::json& msg);  // throws ServiceError
  void hello(const nlohmann::json& msg);
  void create(const nlohmann::json& msg);
  void attach(const std::string& name, bool owned);
  void input(const nlohmann::json& msg);
  void pick(const nlohmann::json& msg);
  void ack(const nlohmann::json& msg);
  void overlay(const nlohmann::json& msg);
  std::string session_message_locked(const std::shared_ptr<service::Session>& s);  // mu_ held
  void end_session();
  void sender();
  std::string frame_message(Frame& f);
  void request_close(grpc::Status status, bool immediate);

  service::ServiceCore& core_;
  const std::shared_ptr<const service::BearerToken> token_;
  const std::shared_ptr<ViewerTransport> transport_;

  mutable std::mutex mu_;
  std::condition_variable cv_;
  bool greeted_ = false;
  std::shared_ptr<service::Session> session_;
  bool owned_ = false;  // created by this viewer: ended with it
  scene::FrameState state_;  // the session's frame state as the inputs so far set it (for picking)
  std::optional<scene::Camera> camera_;  // the latest input's camera (what the next frame renders)
  uint64_t last_sequence_ = 0;
  std::optional<service::PendingInput> pending_;
  bool pending_options_ = false;
  std::optional<Frame> slot_;
  uint64_t dropped_since_sent_ = 0, dropped_total_ = 0;
  std::optional<uint64_t> unacknowledged_;  // frame index sent, not yet drawn
  bool queued_ = false, rendering_ = false;
  bool accept_inputs_ = true;
  // The domain-map overlay: the session's own encodings plus DOMAIN_MAP while it is on; a change
  // goes in with the next input rendered.
  std::vector<v1::ImageEncoding> base_encodings_;
  bool domain_map_overlay_ = false, overlay_changed_ = false;
  std::optional<grpc::Status> close_status_;
  bool close_immediate_ = false;
  bool refused_ = false;  // the close frame was sent
  bool closed_ = false;   // the socket is gone
  bool counted_ = false;
  std::thread sender_;
};

}  // namespace strata::http
