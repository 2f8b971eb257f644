#include "service/session_id.h"

#include "service/errors.h"

namespace strata::service {

void check_session_id(const std::string& id, const std::string& field) {
  const std::string rule = "1-63 characters a-z, 0-9 and '-', starting with a letter and not ending with '-'";
  if (id.empty() || id.size() > 63)
    fail_invalid(field + " has " + std::to_string(id.size()) + " characters; a session id has " + rule);
  for (size_t i = 0; i < id.size(); ++i) {
    const unsigned char c = static_cast<unsigned char>(id[i]);
    if (!((c >= 'a' && c <= 'z') || (c >= '0' && c <= '9') || c == '-')) {
      // Printable characters are quoted; others (control bytes, UTF-8) by their code, so the
      // message itself stays clean.
      const std::string shown = (c >= 0x20 && c < 0x7f) ? "'" + std::string(1, char(c)) + "'" : "byte " + std::to_string(c);
      fail_invalid(field + ": " + shown + " at position " + std::to_string(i) + " is not allowed; a session id has " + rule);
    }
  }
  if (id.front() < 'a' || id.front() > 'z') fail_invalid(field + " = '" + id + "' does not start with a letter; a session id has " + rule);
  if (id.back() == '-') fail_invalid(field + " = '" + id + "' ends with '-'; a session id has " + rule);
}

}  // namespace strata::service
