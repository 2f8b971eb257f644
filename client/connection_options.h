#pragma once
// How every strata command reaches stratad (or a proxy in front of several): the address, TLS
// (server CA, and a client certificate for mutual TLS) and the bearer token, from the same flags
// on every command; and the session affinity metadata that a session-affine proxy hashes on.
#include <chrono>
#include <cstdint>
#include <memory>
#include <string>

#include <CLI/CLI.hpp>
#include <grpcpp/grpcpp.h>

namespace strata::client {

struct ConnectionOptions {
  std::string server = "127.0.0.1:50051";  // stratad or a proxy, host:port
  std::string tls_ca;                      // PEM CA that signed the server's certificate: TLS
  std::string tls_cert, tls_key;           // PEM client certificate and key: mutual TLS
  std::string auth_token_file;             // sent as 'authorization: Bearer <token>' on every call
};

// --server, --tls-ca, --tls-cert, --tls-key, --auth-token-file on `cmd`.
void add_connection_flags(CLI::App* cmd, ConnectionOptions& options);

// A channel to options.server with the receive/send limits raised; every call on it carries the
// bearer token (when given) and `x-strata-session: <affinity_key>` (when not empty), so that a
// proxy hashing on that header sends all of a session's calls to one daemon. Throws
// std::runtime_error naming the flag for unreadable files or an incomplete client certificate.
std::shared_ptr<grpc::Channel> open_channel(const ConnectionOptions& options, const std::string& affinity_key = "",
                                            uint64_t max_receive_bytes = 4u << 20, uint64_t max_send_bytes = 4u << 20);

// A fresh session id for CreateSessionRequest.session_id ("s" and 16 random hex digits), chosen
// by the client so that the proxy can route CreateSession by it before the session exists.
std::string new_session_id();

// The `x-strata-instance` the server stamped on a finished call's response ("" when none).
std::string instance_of(const grpc::ClientContext& ctx);

}  // namespace strata::client
