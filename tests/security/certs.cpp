#include "certs.h"

#include <fstream>
#include <iterator>
#include <stdexcept>

#include "process.h"

namespace strata::test {
namespace {

// P-256 keys: generated in milliseconds, unlike RSA.
void run_openssl(const std::filesystem::path& dir, const std::string& script) {
  const auto r = run_process({"/bin/bash", "-c", "set -euo pipefail; cd '" + dir.string() + "'; " + script}, 60s);
  if (r.exit_code != 0) throw std::runtime_error("openssl failed:\n" + r.output);
}

void make_ca(const std::filesystem::path& dir, const std::string& name) {
  run_openssl(dir, "openssl req -x509 -newkey ec -pkeyopt ec_paramgen_curve:prime256v1 -nodes -days 2 -subj /CN=" + name +
                       " -keyout " + name + ".key -out " + name + ".pem 2>&1");
}

void make_leaf(const std::filesystem::path& dir, const std::string& ca, const std::string& name, const std::string& ext) {
  std::ofstream(dir / (name + ".ext")) << ext << "\n";
  run_openssl(dir, "openssl req -newkey ec -pkeyopt ec_paramgen_curve:prime256v1 -nodes -subj /CN=" + name + " -keyout " + name +
                       ".key -out " + name + ".csr 2>&1 && openssl x509 -req -in " + name + ".csr -CA " + ca + ".pem -CAkey " + ca +
                       ".key -CAcreateserial -days 2 -extfile " + name + ".ext -out " + name + ".pem 2>&1");
}

}  // namespace

TestCerts::TestCerts() {
  const auto& d = dir.path;
  make_ca(d, "ca");
  make_leaf(d, "ca", "server", "subjectAltName=IP:127.0.0.1,DNS:localhost\nextendedKeyUsage=serverAuth");
  make_leaf(d, "ca", "client", "extendedKeyUsage=clientAuth");
  make_ca(d, "otherca");
  make_leaf(d, "otherca", "otherclient", "extendedKeyUsage=clientAuth");
  ca = d / "ca.pem";
  server_cert = d / "server.pem";
  server_key = d / "server.key";
  client_cert = d / "client.pem";
  client_key = d / "client.key";
  other_ca = d / "otherca.pem";
  other_client_cert = d / "otherclient.pem";
  other_client_key = d / "otherclient.key";
}

std::string read_text(const std::filesystem::path& p) {
  std::ifstream in(p, std::ios::binary);
  if (!in) throw std::runtime_error("cannot read " + p.string());
  return std::string(std::istreambuf_iterator<char>(in), {});
}

}  // namespace strata::test
