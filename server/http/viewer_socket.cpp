#include "http/viewer_socket.h"

namespace strata::http {
namespace {

// A close frame holds a 2-byte code and at most 123 bytes of reason; cut it at a UTF-8 boundary.
std::string close_reason(const std::string& s) {
  constexpr size_t k_max = 123;
  if (s.size() <= k_max) return s;
  size_t n = k_max;
  while (n > 0 && (uint8_t(s[n]) & 0xC0) == 0x80) --n;
  return s.substr(0, n);
}

class ConnectionTransport final : public ViewerTransport {
 public:
  explicit ConnectionTransport(mg_connection* conn) : conn_(conn) {}

  bool send_text(const std::string& text) override { return send(MG_WEBSOCKET_OPCODE_TEXT, text); }
  bool send_binary(const std::string& bytes) override { return send(MG_WEBSOCKET_OPCODE_BINARY, bytes); }
  void close(int code, const std::string& reason) override {
    std::string payload = {char((code >> 8) & 0xff), char(code & 0xff)};
    payload += close_reason(reason);
    send(MG_WEBSOCKET_OPCODE_CONNECTION_CLOSE, payload);
    std::lock_guard lock(mu_);
    closed_ = true;
  }
  // The connection is gone (civetweb's close handler): nothing may touch it any more.
  void detach() {
    std::lock_guard lock(mu_);
    closed_ = true;
    conn_ = nullptr;
  }

 private:
  bool send(int opcode, const std::string& bytes) {
    std::lock_guard lock(mu_);  // held across the write: detach() waits for it
    if (closed_ || !conn_) return false;
    mg_lock_connection(conn_);
    const int n = mg_websocket_write(conn_, opcode, bytes.data(), bytes.size());
    mg_unlock_connection(conn_);
    return n > 0;
  }

  std::mutex mu_;
  mg_connection* conn_;
  bool closed_ = false;
};

}  // namespace

bool ViewerSocketHandler::handleConnection(CivetServer*, const mg_connection*) { return true; }

void ViewerSocketHandler::handleReadyState(CivetServer*, mg_connection* conn) {
  auto transport = std::make_shared<ConnectionTransport>(conn);
  auto viewer = std::make_shared<ViewerStream>(core_, token_, transport);
  size_t n = 0;
  {
    std::lock_guard lock(mu_);
    n = viewers_.size();
    viewers_[conn] = Viewer{viewer, {}};
  }
  mg_set_user_connection_data(conn, transport.get());
  viewer->start();
  if (n >= k_max_viewers)
    viewer->refuse(4429, "too many viewers connected (at most " + std::to_string(k_max_viewers) + ")");
}

bool ViewerSocketHandler::handleData(CivetServer*, mg_connection* conn, int bits, char* data, size_t data_len) {
  const int opcode = bits & 0xf;
  const bool final = (bits & 0x80) != 0;
  std::shared_ptr<ViewerStream> viewer;
  std::string message;
  bool complete = false, oversize = false;
  {
    // civetweb hands long messages over in pieces (and clients may fragment them): they are put
    // together here, up to k_max_viewer_message.
    std::lock_guard lock(mu_);
    auto it = viewers_.find(conn);
    if (it == viewers_.end()) return false;
    viewer = it->second.stream;
    auto& partial = it->second.partial;
    if (opcode == MG_WEBSOCKET_OPCODE_TEXT || opcode == MG_WEBSOCKET_OPCODE_CONTINUATION) {
      oversize = partial.size() + data_len > k_max_viewer_message;
      if (!oversize) partial.append(data, data_len);
      if (final || oversize) {
        complete = true;
        message = std::move(partial);
        partial.clear();
      }
    }
  }
  // After a close frame went out only the page's answering close is awaited (what else arrives is
  // dropped); the connection stays open for it, so that the page reads the close code and reason
  // (closing the socket at once would lose them). A page that never answers is dropped after
  // websocket_timeout_ms without a message.
  if (opcode == MG_WEBSOCKET_OPCODE_CONNECTION_CLOSE) return false;
  if (viewer->closing()) return true;
  switch (opcode) {
    case MG_WEBSOCKET_OPCODE_TEXT:
    case MG_WEBSOCKET_OPCODE_CONTINUATION:
      if (oversize) viewer->refuse(1009, "a message exceeds the limit of " + std::to_string(k_max_viewer_message) + " bytes");
      else if (complete) viewer->on_text(message);
      return true;
    case MG_WEBSOCKET_OPCODE_PING:
    case MG_WEBSOCKET_OPCODE_PONG: return true;
    default: viewer->refuse(1003, "binary messages are not accepted; messages are JSON text"); return true;
  }
}

void ViewerSocketHandler::handleClose(CivetServer*, const mg_connection* conn) {
  std::shared_ptr<ViewerStream> viewer;
  {
    std::lock_guard lock(mu_);
    auto it = viewers_.find(conn);
    if (it == viewers_.end()) return;
    viewer = std::move(it->second.stream);
    viewers_.erase(it);
  }
  if (auto* t = static_cast<ConnectionTransport*>(mg_get_user_connection_data(conn))) t->detach();
  viewer->on_closed();
}

void ViewerSocketHandler::close_all() {
  std::vector<std::shared_ptr<ViewerStream>> all;
  {
    std::lock_guard lock(mu_);
    for (auto& [conn, v] : viewers_) all.push_back(v.stream);
  }
  for (auto& v : all) v->end(grpc::Status(grpc::StatusCode::UNAVAILABLE, "stratad is stopping"));
}

}  // namespace strata::http
