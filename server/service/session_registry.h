#pragma once
// The live sessions by name, the max_sessions limit, idle expiry, and a memory of recently removed
// names so that NOT_FOUND can say whether a session expired, was deleted, or never existed.
#include <chrono>
#include <deque>
#include <functional>
#include <map>
#include <memory>
#include <mutex>
#include <string>
#include <vector>

#include "service/config.h"
#include "service/metrics.h"
#include "service/session.h"
#include "service/session_id.h"

namespace strata::service {

class SessionRegistry {
 public:
  SessionRegistry(const ServiceConfig& config, ServiceMetrics& metrics);

  // Reserves a place (RESOURCE_EXHAUSTED naming max_sessions when every place is taken), then
  // calls make(name) outside the lock; its exceptions give the place back.
  std::shared_ptr<Session> create(const std::function<std::shared_ptr<Session>(const std::string& name)>& make);
  // The same with the client's {session} id (CreateSessionRequest.session_id; empty: the server
  // picks one): INVALID_ARGUMENT naming `field` for a malformed id, ALREADY_EXISTS when a live or
  // reserved session has it.
  std::shared_ptr<Session> create(const std::string& requested_id, const std::string& field,
                                  const std::function<std::shared_ptr<Session>(const std::string& name)>& make);
  // INVALID_ARGUMENT for a malformed name (`field` names it), NOT_FOUND for unknown, deleted or expired.
  std::shared_ptr<Session> get(const std::string& name, const std::string& field) const;
  std::vector<std::shared_ptr<Session>> list() const;  // ordered by name
  // Removes the session and ends its stream with NOT_FOUND; false when it is not there.
  bool remove(const std::string& name, const std::string& why);
  // Removes the sessions idle for longer than the idle timeout; returns how many.
  size_t expire_idle(std::chrono::steady_clock::time_point now);
  size_t size() const;

 private:
  std::string new_name();
  void remember_removed_locked(const std::string& name, const std::string& why);

  const ServiceConfig& config_;
  ServiceMetrics& metrics_;
  mutable std::mutex mu_;
  std::map<std::string, std::shared_ptr<Session>> sessions_;
  uint32_t reserved_ = 0;
  std::map<std::string, int> reserved_names_;  // names being created (make() runs outside the lock)
  std::map<std::string, std::string> removed_;  // name -> why, bounded
  std::deque<std::string> removed_order_;
};

// "sessions/{session}" with {session} of 1-63 characters [a-z0-9-].
bool is_session_name(const std::string& name);

}  // namespace strata::service
