#pragma once
// Client-chosen session ids (CreateSessionRequest.session_id, AIP-122/133), on their own so that
// the validation fuzzers (tests/fuzz) can run them without the rest of the service.
#include <string>

namespace strata::service {

// Checks a client-chosen {session} id: 1-63 characters a-z, 0-9, '-', a letter first, not '-'
// last. Throws ServiceError (INVALID_ARGUMENT) naming `field`, the rule and the offending character.
void check_session_id(const std::string& id, const std::string& field);

}  // namespace strata::service
