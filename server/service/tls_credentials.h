#pragma once
// The server's transport credentials from `--tls-cert`/`--tls-key`/`--tls-client-ca`, and the rule
// that keeps a plaintext, unauthenticated daemon on loopback.
#include <memory>
#include <string>

#include <grpcpp/security/server_credentials.h>

#include "service/config.h"

namespace strata::service {

// TLS when tls_cert and tls_key are given (mutual TLS, clients' certificates required and
// verified, when tls_client_ca is also given), else insecure. Throws std::invalid_argument naming
// the flag for a missing half, an unreadable or non-PEM file, or a client CA without TLS.
std::shared_ptr<grpc::ServerCredentials> server_credentials(const SecurityConfig& security);

// Throws std::invalid_argument when `listen` reaches beyond loopback (any address other than
// 127.0.0.0/8, ::1 or localhost) while the server has neither TLS nor a token and `insecure` is off.
void check_exposure(const std::string& listen, const SecurityConfig& security);

// Whether the host part of host:port is a loopback address or name.
bool is_loopback_listen(const std::string& listen);

// The whole content of a PEM file; std::invalid_argument naming `flag` when it cannot be read
// or holds no PEM block.
std::string read_pem(const std::string& flag, const std::string& path);

}  // namespace strata::service
