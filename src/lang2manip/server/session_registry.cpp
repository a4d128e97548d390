#include "lang2manip/server/session_registry.hpp"

#include "lang2manip/server/api_types.hpp"

namespace lang2manip {

SessionRegistry::SessionRegistry(std::size_t capacity, std::chrono::seconds idleTimeout)
    : capacity_(capacity), idleTimeout_(idleTimeout) {}

std::shared_ptr<SessionRegistry::Entry> SessionRegistry::acquire(const std::string& client, bool create) {
  checkClientId(client);
  const std::lock_guard lock(mutex_);
  auto found = sessions_.find(client);
  if (found == sessions_.end()) {
    if (!create) throw ApiError(404, "not_found", "client \"" + client + "\" has no session; POST /api/sessions/" + client + "/openProblem first");
    if (sessions_.size() >= capacity_ && !evictIdle()) {
      throw ApiError(429, "too_many_sessions", "the server holds " + std::to_string(capacity_) +
                                                   " sessions, its limit; close one with DELETE /api/sessions/{client}");
    }
    found = sessions_.emplace(client, std::make_shared<Entry>()).first;
    found->second->lastUse = std::chrono::steady_clock::now();
  }
  ++found->second->users;
  return found->second;
}

void SessionRegistry::release(Entry& entry) {
  const std::lock_guard lock(mutex_);
  --entry.users;
  entry.lastUse = std::chrono::steady_clock::now();
}

bool SessionRegistry::evictIdle() {
  const auto now = std::chrono::steady_clock::now();
  auto oldest = sessions_.end();
  for (auto it = sessions_.begin(); it != sessions_.end(); ++it) {
    if (it->second->users > 0 || now - it->second->lastUse < idleTimeout_) continue;
    if (oldest == sessions_.end() || it->second->lastUse < oldest->second->lastUse) oldest = it;
  }
  if (oldest == sessions_.end()) return false;
  sessions_.erase(oldest);
  return true;
}

void SessionRegistry::use(const std::string& client, bool create, const std::function<void(ClientSession&)>& work) {
  const std::shared_ptr<Entry> entry = acquire(client, create);
  struct Release {
    SessionRegistry& registry;
    Entry& entry;
    ~Release() { registry.release(entry); }
  } release{*this, *entry};
  const std::lock_guard lock(entry->mutex);
  work(entry->session);
}

bool SessionRegistry::remove(const std::string& client) {
  checkClientId(client);
  std::shared_ptr<Entry> entry;
  {
    const std::lock_guard lock(mutex_);
    const auto found = sessions_.find(client);
    if (found == sessions_.end()) return false;
    entry = found->second;
    sessions_.erase(found);
  }
  // The session ends when the last request using it returns (the shared pointer).
  return true;
}

std::size_t SessionRegistry::size() const {
  const std::lock_guard lock(mutex_);
  return sessions_.size();
}

}  // namespace lang2manip
