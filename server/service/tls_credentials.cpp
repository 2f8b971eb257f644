#include "service/tls_credentials.h"

#include <fstream>
#include <iterator>
#include <stdexcept>

#include <arpa/inet.h>
#include <netinet/in.h>

#include <grpcpp/security/server_credentials.h>

namespace strata::service {

std::string read_pem(const std::string& flag, const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) throw std::invalid_argument(flag + " " + path + ": cannot be read");
  std::string pem((std::istreambuf_iterator<char>(in)), {});
  if (pem.find("-----BEGIN ") == std::string::npos)
    throw std::invalid_argument(flag + " " + path + ": not a PEM file (no '-----BEGIN' line)");
  return pem;
}

std::shared_ptr<grpc::ServerCredentials> server_credentials(const SecurityConfig& s) {
  const bool cert = !s.tls_cert.empty(), key = !s.tls_key.empty();
  if (cert != key) throw std::invalid_argument(cert ? "--tls-cert needs --tls-key (the certificate's private key)"
                                                    : "--tls-key needs --tls-cert (the certificate chain)");
  if (!cert) {
    if (!s.tls_client_ca.empty())
      throw std::invalid_argument("--tls-client-ca needs --tls-cert and --tls-key: client certificates are checked only over TLS");
    return grpc::InsecureServerCredentials();
  }
  grpc::SslServerCredentialsOptions options;
  options.pem_key_cert_pairs.push_back({read_pem("--tls-key", s.tls_key.string()), read_pem("--tls-cert", s.tls_cert.string())});
  if (!s.tls_client_ca.empty()) {
    options.pem_root_certs = read_pem("--tls-client-ca", s.tls_client_ca.string());
    options.client_certificate_request = GRPC_SSL_REQUEST_AND_REQUIRE_CLIENT_CERTIFICATE_AND_VERIFY;
  } else {
    options.client_certificate_request = GRPC_SSL_DONT_REQUEST_CLIENT_CERTIFICATE;
  }
  return grpc::SslServerCredentials(options);
}

bool is_loopback_listen(const std::string& listen) {
  if (listen.rfind("unix:", 0) == 0 || listen.rfind("unix-abstract:", 0) == 0) return true;  // local sockets
  std::string host;
  if (!listen.empty() && listen.front() == '[') {
    const auto close = listen.find(']');
    if (close == std::string::npos) return false;
    host = listen.substr(1, close - 1);
  } else {
    const auto colon = listen.rfind(':');
    host = colon == std::string::npos ? listen : listen.substr(0, colon);
  }
  if (host == "localhost") return true;
  in_addr v4{};
  if (inet_pton(AF_INET, host.c_str(), &v4) == 1) return (ntohl(v4.s_addr) >> 24) == 127;  // 127.0.0.0/8
  in6_addr v6{};
  if (inet_pton(AF_INET6, host.c_str(), &v6) == 1) return IN6_IS_ADDR_LOOPBACK(&v6);
  return false;  // other names and the wildcard addresses (0.0.0.0, [::]) may reach the network
}

void check_exposure(const std::string& listen, const SecurityConfig& s) {
  if (s.insecure || is_loopback_listen(listen)) return;
  if (!s.tls_cert.empty() || !s.auth_token_file.empty()) return;
  throw std::invalid_argument("--listen " + listen +
                              " reaches beyond loopback without TLS or a token: give --tls-cert/--tls-key (and --tls-client-ca "
                              "for mutual TLS) or --auth-token-file, or --insecure to serve it in the clear anyway");
}

}  // namespace strata::service
