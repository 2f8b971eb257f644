// TLS and mutual TLS with certificates made by openssl for this test; the rule that a daemon
// without TLS or a token stays on loopback; and the strata client's --tls-* and --auth-token-file
// against a stratad process.
#include <fstream>

#include "certs.h"
#include "harness.h"
#include "process.h"
#include "service/tls_credentials.h"

namespace strata::test {
namespace {

std::shared_ptr<grpc::Channel> tls_channel(const std::string& address, const TestCerts& c, bool client_cert,
                                           const std::filesystem::path& cert = {}, const std::filesystem::path& key = {}) {
  grpc::SslCredentialsOptions o;
  o.pem_root_certs = read_text(c.ca);
  if (client_cert) {
    o.pem_cert_chain = read_text(cert.empty() ? c.client_cert : cert);
    o.pem_private_key = read_text(key.empty() ? c.client_key : key);
  }
  return grpc::CreateChannel(address, grpc::SslCredentials(o));
}

grpc::StatusCode status_code_over(const std::shared_ptr<grpc::Channel>& channel) {
  auto stub = v1::RenderService::NewStub(channel);
  grpc::ClientContext ctx;
  ctx.set_deadline(std::chrono::system_clock::now() + 5s);
  v1::ServerStatus st;
  return stub->GetServerStatus(&ctx, {}, &st).error_code();
}

class TlsTest : public ServiceTest {
 protected:
  void SetUp() override {
    config_.security.tls_cert = certs_.server_cert;
    config_.security.tls_key = certs_.server_key;
    // The fixture's own stub is plaintext; these tests make their own channels.
    ServiceTest::SetUp();
  }
  TestCerts certs_;
};

TEST_F(TlsTest, TlsClientsWorkAndPlaintextClientsDoNot) {
  EXPECT_EQ(status_code_over(tls_channel(address(), certs_, false)), grpc::StatusCode::OK);
  EXPECT_EQ(status_code_over(loopback_channel(address())), grpc::StatusCode::UNAVAILABLE);
  // A stream over TLS renders frames.
  auto stub = v1::RenderService::NewStub(tls_channel(address(), certs_, false));
  const auto s = create_ok(*stub, session_request("cornell", 16, 16));
  EXPECT_EQ(stream_frames(*stub, s.name(), 2).size(), 2u);
}

TEST_F(TlsTest, AClientTrustingAnotherCaRefusesTheServer) {
  grpc::SslCredentialsOptions o;
  o.pem_root_certs = read_text(certs_.other_ca);
  EXPECT_EQ(status_code_over(grpc::CreateChannel(address(), grpc::SslCredentials(o))), grpc::StatusCode::UNAVAILABLE);
}

TEST_F(TlsTest, MutualTlsNeedsAClientCertificateFromTheClientCa) {
  auto config = config_;
  config.security.tls_client_ca = certs_.ca;
  start(config);
  EXPECT_EQ(status_code_over(tls_channel(address(), certs_, true)), grpc::StatusCode::OK);
  EXPECT_EQ(status_code_over(tls_channel(address(), certs_, false)), grpc::StatusCode::UNAVAILABLE);
  EXPECT_EQ(status_code_over(tls_channel(address(), certs_, true, certs_.other_client_cert, certs_.other_client_key)),
            grpc::StatusCode::UNAVAILABLE);
}

TEST(TlsConfigTest, IncompleteOrUnreadableTlsSettingsNameTheFlag) {
  TestCerts certs;
  std::ofstream(certs.dir.path / "not.pem") << "hello\n";
  const std::vector<std::pair<service::SecurityConfig, std::string>> cases = {
      {{certs.server_cert, {}, {}, {}, false}, "--tls-cert needs --tls-key"},
      {{{}, certs.server_key, {}, {}, false}, "--tls-key needs --tls-cert"},
      {{{}, {}, certs.ca, {}, false}, "--tls-client-ca needs --tls-cert"},
      {{certs.dir.path / "missing.pem", certs.server_key, {}, {}, false}, "--tls-cert"},
      {{certs.server_cert, certs.dir.path / "not.pem", {}, {}, false}, "--tls-key"},
  };
  for (const auto& [sec, expected] : cases) {
    SCOPED_TRACE(expected);
    try {
      service::server_credentials(sec);
      ADD_FAILURE() << "accepted";
    } catch (const std::invalid_argument& e) {
      EXPECT_NE(std::string(e.what()).find(expected), std::string::npos) << e.what();
    }
  }
}

TEST(ExposureTest, LoopbackAddressesAreRecognised) {
  for (const char* a : {"127.0.0.1:50051", "127.1.2.3:0", "localhost:1", "[::1]:50051", "unix:/tmp/s"})
    EXPECT_TRUE(service::is_loopback_listen(a)) << a;
  for (const char* a : {"0.0.0.0:50051", "[::]:50051", "10.0.0.5:1", "example.com:1", "127.example.com:1", "[::ffff:10.0.0.1]:1"})
    EXPECT_FALSE(service::is_loopback_listen(a)) << a;
}

TEST(ExposureTest, BeyondLoopbackNeedsTlsOrATokenOrInsecure) {
  service::SecurityConfig none;
  try {
    service::check_exposure("0.0.0.0:50051", none);
    ADD_FAILURE() << "accepted";
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("--insecure"), std::string::npos) << e.what();
  }
  EXPECT_NO_THROW(service::check_exposure("127.0.0.1:50051", none));
  service::SecurityConfig token;
  token.auth_token_file = "/some/token";
  EXPECT_NO_THROW(service::check_exposure("0.0.0.0:50051", token));
  service::SecurityConfig tls;
  tls.tls_cert = "/c.pem";
  tls.tls_key = "/k.pem";
  EXPECT_NO_THROW(service::check_exposure("[::]:50051", tls));
  service::SecurityConfig insecure;
  insecure.insecure = true;
  EXPECT_NO_THROW(service::check_exposure("0.0.0.0:50051", insecure));
}

TEST(ExposureTest, StratadRefusesToServeBeyondLoopbackInTheClear) {
  // Refused before it binds: nothing listens, and the message says what to do.
  const auto r = run_process({stratad_path(), "serve", "--listen", "0.0.0.0:0"}, 60s);
  EXPECT_NE(r.exit_code, 0);
  EXPECT_NE(r.output.find("beyond loopback"), std::string::npos) << r.output;
}

// stratad serve with TLS, mutual TLS and a token; strata stream and health with the same flags.
TEST(SecureCliTest, StrataCommandsTakeTlsAndTokenFlags) {
  TestCerts certs;
  TempDir dir;
  std::ofstream(dir.path / "token") << "cli-token-0123456789abcdef\n";
  std::ofstream(dir.path / "wrong") << "not-the-token-0123456789\n";
  const std::string port_file = (dir.path / "port").string();
  Process daemon({stratad_path(), "serve", "--listen", "127.0.0.1:0", "--port-file", port_file, "--instance-id", "secure-1",
                  "--tls-cert", certs.server_cert.string(), "--tls-key", certs.server_key.string(), "--tls-client-ca",
                  certs.ca.string(), "--auth-token-file", (dir.path / "token").string(),
                  "--no-progressive-start"});
  std::string address;
  ASSERT_TRUE(wait_until([&] {
    std::ifstream in(port_file);
    int port = 0;
    if (!(in >> port) || port <= 0) return false;
    address = "127.0.0.1:" + std::to_string(port);
    return true;
  }, 60s)) << daemon.output();
  const std::vector<std::string> tls = {"--server", address, "--tls-ca", certs.ca.string(), "--tls-cert", certs.client_cert.string(),
                                        "--tls-key", certs.client_key.string()};
  auto with = [&](std::vector<std::string> argv, const std::vector<std::string>& more) {
    argv.insert(argv.end(), more.begin(), more.end());
    return argv;
  };
  const auto health = run_process(with({strata_path(), "health", "--wait", "30"}, tls), 60s);
  EXPECT_EQ(health.exit_code, 0) << health.output;
  const std::vector<std::string> stream = {strata_path(), "stream", "--method", "pt", "--width", "16", "--height", "16", "--frames", "2",
                                           "--session-id", "cli-session", "--out", (dir.path / "out").string()};
  const auto ok = run_process(with(with(stream, tls), {"--auth-token-file", (dir.path / "token").string()}), 120s);
  ASSERT_EQ(ok.exit_code, 0) << ok.output;
  EXPECT_NE(ok.output.find("sessions/cli-session"), std::string::npos) << ok.output;
  EXPECT_NE(ok.output.find("instance secure-1"), std::string::npos) << ok.output;
  const std::string frames = read_text(dir.path / "out" / "frames.json");
  EXPECT_NE(frames.find("\"DeleteSession\": \"secure-1\""), std::string::npos);
  EXPECT_NE(frames.find("\"Stream\": \"secure-1\""), std::string::npos);

  const auto no_token = run_process(with(stream, tls), 60s);
  EXPECT_NE(no_token.exit_code, 0);
  EXPECT_NE(no_token.output.find("UNAUTHENTICATED"), std::string::npos) << no_token.output;
  const auto wrong = run_process(with(with(stream, tls), {"--auth-token-file", (dir.path / "wrong").string()}), 60s);
  EXPECT_NE(wrong.exit_code, 0);
  EXPECT_NE(wrong.output.find("UNAUTHENTICATED"), std::string::npos) << wrong.output;
  const auto no_cert = run_process(with(stream, {"--server", address, "--tls-ca", certs.ca.string(), "--auth-token-file",
                                                 (dir.path / "token").string()}),
                                   60s);
  EXPECT_NE(no_cert.exit_code, 0);
  EXPECT_NE(no_cert.output.find("UNAVAILABLE"), std::string::npos) << no_cert.output;
  daemon.signal(SIGTERM);
  EXPECT_EQ(daemon.wait_exit(30s), 0) << daemon.output();
}

}  // namespace
}  // namespace strata::test
