#pragma once
// /view/ws on civetweb: each WebSocket connection gets a ViewerStream (viewer_stream.h) whose
// transport writes to the connection under civetweb's connection lock. At most k_max_viewers
// sockets at once (each holds one of civetweb's worker threads); one more is closed with a reason.
#include <map>
#include <memory>
#include <mutex>

#include <CivetServer.h>

#include "http/viewer_stream.h"

namespace strata::http {

class ViewerSocketHandler final : public CivetWebSocketHandler {
 public:
  static constexpr size_t k_max_viewers = 16;

  ViewerSocketHandler(service::ServiceCore& core, std::shared_ptr<const service::BearerToken> token)
      : core_(core), token_(std::move(token)) {}
  // Closes every viewer's socket (server shutdown; civetweb then ends the connections).
  void close_all();

  bool handleConnection(CivetServer* server, const mg_connection* conn) override;
  void handleReadyState(CivetServer* server, mg_connection* conn) override;
  bool handleData(CivetServer* server, mg_connection* conn, int bits, char* data, size_t data_len) override;
  void handleClose(CivetServer* server, const mg_connection* conn) override;

 private:
  struct Viewer {
    std::shared_ptr<ViewerStream> stream;
    std::string partial;  // a message civetweb hands over in pieces (no FIN bit yet)
  };

  service::ServiceCore& core_;
  const std::shared_ptr<const service::BearerToken> token_;
  std::mutex mu_;
  std::map<const mg_connection*, Viewer> viewers_;
};

}  // namespace strata::http
