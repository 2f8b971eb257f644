#pragma once
// Bearer-token authentication of RenderService calls (`stratad serve --auth-token-file`): the
// client sends `authorization: Bearer <token>`; a missing, malformed or different token is
// UNAUTHENTICATED. The comparison takes the same time wherever the tokens differ, so response
// times do not reveal how much of a guess was right.
#include <filesystem>
#include <map>
#include <string>

#include <grpcpp/support/status.h>
#include <grpcpp/support/string_ref.h>

namespace strata::service {

class BearerToken {
 public:
  // Reads the token from `path`: the file's content with trailing whitespace (a final newline)
  // removed; 16-4096 printable ASCII characters without spaces. Throws std::invalid_argument
  // naming the file and what is wrong with it (never the token itself).
  static BearerToken load(const std::filesystem::path& path);
  explicit BearerToken(std::string token);

  // OK when the metadata carries `authorization: Bearer <token>`, else UNAUTHENTICATED saying
  // what was missing (never echoing what was sent).
  grpc::Status check(const std::multimap<grpc::string_ref, grpc::string_ref>& metadata) const;

 private:
  std::string token_;
};

// a == b in time independent of the contents (both are hashed, the digests compared in constant time).
bool constant_time_equal(std::string_view a, std::string_view b);

}  // namespace strata::service
