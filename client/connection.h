#pragma once
// Channels to stratad and the errors of calls made over them.
#include <chrono>
#include <cstdint>
#include <memory>
#include <stdexcept>
#include <string>

#include <grpcpp/grpcpp.h>

namespace strata::client {

// A failed RPC: the method, the status code's name and the server's message.
struct RpcError : std::runtime_error {
  RpcError(const std::string& method, const grpc::Status& status);  // as_seen_through_proxies(status)
  grpc::StatusCode code;

 private:
  RpcError(const std::string& method, const grpc::Status& status, int);
};

// UNKNOWN "No status received" (a proxy's backend went away mid-call) as UNAVAILABLE; other
// statuses as they are.
grpc::Status as_seen_through_proxies(const grpc::Status& status);

std::string status_code_name(grpc::StatusCode code);

// Channel arguments every strata channel shares: the message limits, and a retry policy for the
// read-only calls (GetServerStatus, GetSession, ListSessions, ListScenes): a connection that a proxy
// or the network closes under such a call (UNAVAILABLE "Socket closed") is retried up to 3 more
// times with backoff, as nothing on the server changed. Calls that change state (CreateSession,
// Stream, DeleteSession, RenderReference) and the health check are never retried: their failures
// are reported as they happen.
grpc::ChannelArguments channel_arguments(uint64_t max_receive_bytes, uint64_t max_send_bytes);

// An insecure channel (stratad listens on loopback by default) whose receive limit is raised to
// `max_receive_bytes` (frames) and send limit to `max_send_bytes` (inline scenes).
std::shared_ptr<grpc::Channel> connect(const std::string& address, uint64_t max_receive_bytes = 4u << 20,
                                       uint64_t max_send_bytes = 4u << 20);

// Sets a deadline `timeout` from now on `ctx`.
void set_deadline(grpc::ClientContext& ctx, std::chrono::milliseconds timeout);

}  // namespace strata::client
