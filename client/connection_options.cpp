#include "connection_options.h"

#include "connection.h"

#include <algorithm>
#include <climits>
#include <fstream>
#include <iterator>
#include <random>
#include <stdexcept>

#include <grpcpp/support/client_interceptor.h>

namespace strata::client {
namespace {

std::string read_file(const std::string& flag, const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) throw std::runtime_error(flag + " " + path + ": cannot be read");
  return std::string((std::istreambuf_iterator<char>(in)), {});
}

// Adds fixed metadata to every call of the channel (gRPC refuses call credentials on plaintext
// channels, and the token must reach a plaintext daemon on loopback or behind a proxy too).
class MetadataInterceptor final : public grpc::experimental::Interceptor {
 public:
  MetadataInterceptor(const std::string& token, const std::string& session) : token_(token), session_(session) {}
  void Intercept(grpc::experimental::InterceptorBatchMethods* methods) override {
    if (methods->QueryInterceptionHookPoint(grpc::experimental::InterceptionHookPoints::PRE_SEND_INITIAL_METADATA)) {
      auto* md = methods->GetSendInitialMetadata();
      if (!token_.empty()) md->emplace("authorization", "Bearer " + token_);
      if (!session_.empty()) md->emplace("x-strata-session", session_);
    }
    methods->Proceed();
  }

 private:
  const std::string& token_;
  const std::string& session_;
};

class MetadataInterceptorFactory final : public grpc::experimental::ClientInterceptorFactoryInterface {
 public:
  MetadataInterceptorFactory(std::string token, std::string session) : token_(std::move(token)), session_(std::move(session)) {}
  grpc::experimental::Interceptor* CreateClientInterceptor(grpc::experimental::ClientRpcInfo*) override {
    return new MetadataInterceptor(token_, session_);
  }

 private:
  std::string token_, session_;
};

}  // namespace

void add_connection_flags(CLI::App* cmd, ConnectionOptions& o) {
  cmd->add_option("--server", o.server, "stratad (or a proxy in front of several) host:port")->capture_default_str();
  cmd->add_option("--tls-ca", o.tls_ca, "PEM CA of the server's certificate: connect over TLS");
  cmd->add_option("--tls-cert", o.tls_cert, "PEM client certificate for mutual TLS (with --tls-key; implies TLS)");
  cmd->add_option("--tls-key", o.tls_key, "PEM private key of --tls-cert");
  cmd->add_option("--auth-token-file", o.auth_token_file, "file holding the bearer token to send on every call");
}

std::shared_ptr<grpc::Channel> open_channel(const ConnectionOptions& o, const std::string& affinity_key, uint64_t max_receive_bytes,
                                            uint64_t max_send_bytes) {
  if (o.tls_cert.empty() != o.tls_key.empty())
    throw std::runtime_error(o.tls_cert.empty() ? "--tls-key needs --tls-cert" : "--tls-cert needs --tls-key");
  std::shared_ptr<grpc::ChannelCredentials> credentials;
  if (o.tls_ca.empty() && o.tls_cert.empty()) {
    credentials = grpc::InsecureChannelCredentials();
  } else {
    grpc::SslCredentialsOptions ssl;
    if (!o.tls_ca.empty()) ssl.pem_root_certs = read_file("--tls-ca", o.tls_ca);  // else the system's roots
    if (!o.tls_cert.empty()) {
      ssl.pem_cert_chain = read_file("--tls-cert", o.tls_cert);
      ssl.pem_private_key = read_file("--tls-key", o.tls_key);
    }
    credentials = grpc::SslCredentials(ssl);
  }
  std::string token;
  if (!o.auth_token_file.empty()) {
    token = read_file("--auth-token-file", o.auth_token_file);
    while (!token.empty() && std::isspace(static_cast<unsigned char>(token.back()))) token.pop_back();
    if (token.empty()) throw std::runtime_error("--auth-token-file " + o.auth_token_file + " is empty");
  }
  auto args = channel_arguments(max_receive_bytes, max_send_bytes);
  std::vector<std::unique_ptr<grpc::experimental::ClientInterceptorFactoryInterface>> interceptors;
  interceptors.push_back(std::make_unique<MetadataInterceptorFactory>(std::move(token), affinity_key));
  return grpc::experimental::CreateCustomChannelWithInterceptors(o.server, credentials, args, std::move(interceptors));
}

std::string new_session_id() {
  std::random_device rd;
  std::mt19937_64 rng((uint64_t(rd()) << 32) ^ rd());
  static const char* digits = "0123456789abcdef";
  std::string id = "s";
  uint64_t bits = rng();
  for (int i = 0; i < 16; ++i, bits >>= 4) id += digits[bits & 15];
  return id;
}

std::string instance_of(const grpc::ClientContext& ctx) {
  const auto& md = ctx.GetServerInitialMetadata();
  auto it = md.find("x-strata-instance");
  return it == md.end() ? "" : std::string(it->second.data(), it->second.size());
}

}  // namespace strata::client
