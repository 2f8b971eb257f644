#include "service/auth_token.h"

#include <fstream>
#include <iterator>
#include <stdexcept>

#include <openssl/crypto.h>
#include <openssl/sha.h>

namespace strata::service {
namespace {

constexpr size_t k_min_token = 16, k_max_token = 4096;
constexpr std::string_view k_scheme = "Bearer ";

}  // namespace

bool constant_time_equal(std::string_view a, std::string_view b) {
  // Comparing fixed-size digests hides the length as well as the content: the time depends on
  // neither where the strings first differ nor how long the secret is.
  unsigned char da[SHA256_DIGEST_LENGTH], db[SHA256_DIGEST_LENGTH];
  SHA256(reinterpret_cast<const unsigned char*>(a.data()), a.size(), da);
  SHA256(reinterpret_cast<const unsigned char*>(b.data()), b.size(), db);
  return CRYPTO_memcmp(da, db, sizeof da) == 0;
}

BearerToken BearerToken::load(const std::filesystem::path& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) throw std::invalid_argument("--auth-token-file " + path.string() + ": cannot be read");
  std::string token((std::istreambuf_iterator<char>(in)), {});
  while (!token.empty() && (token.back() == '\n' || token.back() == '\r' || token.back() == ' ' || token.back() == '\t'))
    token.pop_back();
  if (token.size() < k_min_token || token.size() > k_max_token)
    throw std::invalid_argument("--auth-token-file " + path.string() + ": the token has " + std::to_string(token.size()) +
                                " characters; it must have " + std::to_string(k_min_token) + "-" + std::to_string(k_max_token));
  for (char c : token)
    if (c <= 0x20 || c >= 0x7f)
      throw std::invalid_argument("--auth-token-file " + path.string() +
                                  ": the token may only hold printable ASCII characters without spaces");
  return BearerToken(std::move(token));
}

BearerToken::BearerToken(std::string token) : token_(std::move(token)) {}

grpc::Status BearerToken::check(const std::multimap<grpc::string_ref, grpc::string_ref>& metadata) const {
  const auto [first, last] = metadata.equal_range("authorization");
  if (first == last)
    return {grpc::StatusCode::UNAUTHENTICATED, "this server requires the metadata 'authorization: Bearer <token>' (none was sent)"};
  if (std::next(first) != last)
    return {grpc::StatusCode::UNAUTHENTICATED, "more than one 'authorization' metadata entry was sent; send exactly one"};
  const std::string_view value(first->second.data(), first->second.size());
  if (value.substr(0, k_scheme.size()) != k_scheme)
    return {grpc::StatusCode::UNAUTHENTICATED, "the 'authorization' metadata must be 'Bearer <token>'"};
  if (!constant_time_equal(value.substr(k_scheme.size()), token_))
    return {grpc::StatusCode::UNAUTHENTICATED, "the bearer token is not valid for this server"};
  return grpc::Status::OK;
}

}  // namespace strata::service
