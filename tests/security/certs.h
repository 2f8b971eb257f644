#pragma once
// A throwaway PKI made with the `openssl` command for one test: a CA, a server certificate for
// 127.0.0.1 and localhost signed by it, a client certificate signed by it, and a second CA with a
// client certificate of its own (one the server must refuse).
#include <filesystem>
#include <string>

#include "harness.h"

namespace strata::test {

struct TestCerts {
  TestCerts();  // throws std::runtime_error with openssl's output when a step fails
  TempDir dir;
  std::filesystem::path ca, server_cert, server_key, client_cert, client_key;
  std::filesystem::path other_ca, other_client_cert, other_client_key;
};

std::string read_text(const std::filesystem::path& p);

}  // namespace strata::test
