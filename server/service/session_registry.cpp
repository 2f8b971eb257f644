#include "service/session_registry.h"

#include <random>

#include "service/errors.h"

namespace strata::service {
namespace {

constexpr size_t k_removed_memory = 4096;
constexpr const char* k_prefix = "sessions/";

}  // namespace

bool is_session_name(const std::string& name) {
  const std::string prefix = k_prefix;
  if (name.rfind(prefix, 0) != 0) return false;
  const std::string id = name.substr(prefix.size());
  if (id.empty() || id.size() > 63) return false;
  for (char c : id)
    if (!((c >= 'a' && c <= 'z') || (c >= '0' && c <= '9') || c == '-')) return false;
  return true;
}

SessionRegistry::SessionRegistry(const ServiceConfig& config, ServiceMetrics& metrics) : config_(config), metrics_(metrics) {}

std::string SessionRegistry::new_name() {
  static thread_local std::mt19937_64 rng{std::random_device{}()};
  static const char* digits = "0123456789abcdef";
  for (;;) {
    std::string id;
    uint64_t bits = rng();
    for (int i = 0; i < 16; ++i, bits >>= 4) id += digits[bits & 15];
    std::string name = k_prefix + id;
    if (!sessions_.count(name) && !removed_.count(name) && !reserved_names_.count(name)) return name;
  }
}

std::shared_ptr<Session> SessionRegistry::create(const std::function<std::shared_ptr<Session>(const std::string&)>& make) {
  return create("", "session_id", make);
}

std::shared_ptr<Session> SessionRegistry::create(const std::string& requested_id, const std::string& field,
                                                 const std::function<std::shared_ptr<Session>(const std::string&)>& make) {
  if (!requested_id.empty()) check_session_id(requested_id, field);
  std::string name;
  {
    std::lock_guard lock(mu_);
    if (!requested_id.empty()) {
      name = k_prefix + requested_id;
      if (sessions_.count(name) || reserved_names_.count(name))
        fail(grpc::StatusCode::ALREADY_EXISTS, "session '" + name + "' already exists (" + field + " = '" + requested_id +
                                                    "'); pick another id or delete that session first");
    }
    if (sessions_.size() + reserved_ >= config_.limits.max_sessions)
      fail(grpc::StatusCode::RESOURCE_EXHAUSTED,
           "max_sessions = " + std::to_string(config_.limits.max_sessions) +
               " sessions are open; delete one (DeleteSession) or wait for idle ones to expire (idle_timeout = " +
               std::to_string(config_.idle_timeout.count()) + " ms)");
    ++reserved_;
    if (name.empty()) name = new_name();
    ++reserved_names_[name];
  }
  auto unreserve_locked = [&] {
    --reserved_;
    if (--reserved_names_[name] == 0) reserved_names_.erase(name);
  };
  std::shared_ptr<Session> session;
  try {
    session = make(name);
  } catch (...) {
    std::lock_guard lock(mu_);
    unreserve_locked();
    throw;
  }
  std::lock_guard lock(mu_);
  unreserve_locked();
  // A name reused after its session was removed is live again; NOT_FOUND must not call it removed.
  removed_.erase(name);
  sessions_[name] = session;
  metrics_.sessions_created.fetch_add(1);
  return session;
}

std::shared_ptr<Session> SessionRegistry::get(const std::string& name, const std::string& field) const {
  if (!is_session_name(name))
    fail_invalid(field + " = '" + name + "' is not a session name: expected sessions/{session} with {session} of 1-63 characters a-z, 0-9, -");
  std::lock_guard lock(mu_);
  auto it = sessions_.find(name);
  if (it != sessions_.end()) return it->second;
  auto gone = removed_.find(name);
  if (gone != removed_.end()) fail(grpc::StatusCode::NOT_FOUND, "session '" + name + "' " + gone->second);
  fail(grpc::StatusCode::NOT_FOUND, "session '" + name + "' does not exist");
}

std::vector<std::shared_ptr<Session>> SessionRegistry::list() const {
  std::lock_guard lock(mu_);
  std::vector<std::shared_ptr<Session>> out;
  for (const auto& [name, s] : sessions_) out.push_back(s);
  return out;
}

size_t SessionRegistry::size() const {
  std::lock_guard lock(mu_);
  return sessions_.size();
}

void SessionRegistry::remember_removed_locked(const std::string& name, const std::string& why) {
  removed_[name] = why;
  removed_order_.push_back(name);
  while (removed_order_.size() > k_removed_memory) {
    removed_.erase(removed_order_.front());
    removed_order_.pop_front();
  }
}

bool SessionRegistry::remove(const std::string& name, const std::string& why) {
  std::shared_ptr<Session> s;
  {
    std::lock_guard lock(mu_);
    auto it = sessions_.find(name);
    if (it == sessions_.end()) return false;
    s = std::move(it->second);
    sessions_.erase(it);
    remember_removed_locked(name, why);
  }
  if (auto stream = s->stream()) stream->end(grpc::Status(grpc::StatusCode::NOT_FOUND, "session '" + name + "' " + why));
  return true;
}

size_t SessionRegistry::expire_idle(std::chrono::steady_clock::time_point now) {
  const std::string why = "expired after " + std::to_string(config_.idle_timeout.count()) + " ms idle (idle_timeout)";
  std::vector<std::shared_ptr<Session>> expired;
  {
    std::lock_guard lock(mu_);
    for (auto it = sessions_.begin(); it != sessions_.end();) {
      auto since = it->second->idle_since();
      if (since && now - *since > config_.idle_timeout) {
        remember_removed_locked(it->first, why);
        expired.push_back(std::move(it->second));
        it = sessions_.erase(it);
      } else {
        ++it;
      }
    }
  }
  metrics_.sessions_expired.fetch_add(expired.size());
  return expired.size();  // no stream is attached to an idle session; their memory goes with them
}

}  // namespace strata::service
