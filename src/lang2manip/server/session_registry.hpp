#pragma once
/// @file The planning sessions of the server's clients: one PlanningSession per client id,
/// created by openProblem, used by one request at a time (requests of different clients run in
/// parallel), closed by DELETE or evicted when idle longest and the registry is full.

#include <chrono>
#include <cstddef>
#include <functional>
#include <map>
#include <memory>
#include <mutex>
#include <string>

#include "lang2manip/planning/planning_session.hpp"

namespace lang2manip {

/// A client's session with what the server adds to it: the problem's name.
struct ClientSession {
  PlanningSession planning;
  std::string problemName;
};

class SessionRegistry {
 public:
  /// At most `capacity` sessions; sessions idle longer than `idleTimeout` may be evicted to make
  /// room for a new one.
  SessionRegistry(std::size_t capacity, std::chrono::seconds idleTimeout);

  /// Runs `work` on the session of `client` (created when `create` and it does not exist), alone
  /// on that session. Throws ApiError 400 for a malformed client id, 404 when there is no
  /// session and `create` is false, 429 when the registry is full of active sessions.
  void use(const std::string& client, bool create, const std::function<void(ClientSession&)>& work);

  /// Closes the session of `client`; false when there was none. A request using it finishes first.
  bool remove(const std::string& client);

  [[nodiscard]] std::size_t size() const;

 private:
  struct Entry {
    std::mutex mutex;
    ClientSession session;
    std::chrono::steady_clock::time_point lastUse;
    int users = 0;
  };
  std::shared_ptr<Entry> acquire(const std::string& client, bool create);
  void release(Entry& entry);
  bool evictIdle();

  std::size_t capacity_;
  std::chrono::seconds idleTimeout_;
  mutable std::mutex mutex_;
  std::map<std::string, std::shared_ptr<Entry>> sessions_;
};

}  // namespace lang2manip
