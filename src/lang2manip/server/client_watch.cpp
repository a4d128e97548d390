#include "lang2manip/server/client_watch.hpp"

#include <poll.h>

#include <cerrno>
#include <utility>
#include <vector>

namespace lang2manip {

ClientWatch::ClientWatch(std::chrono::milliseconds period) : period_(period), thread_([this] { run(); }) {}

ClientWatch::~ClientWatch() {
  {
    const std::lock_guard<std::mutex> lock(mutex_);
    stopping_ = true;
  }
  wake_.notify_all();
  thread_.join();
}

ClientWatch::Registration::~Registration() {
  if (watch_ != nullptr) watch_->forget(id_);
}

ClientWatch::Registration ClientWatch::watch(int socket, CancelFlag flag) {
  if (socket < 0 || !flag) return {nullptr, 0};
  std::uint64_t id = 0;
  {
    const std::lock_guard<std::mutex> lock(mutex_);
    id = nextId_++;
    entries_.emplace(id, Entry{socket, std::move(flag)});
  }
  wake_.notify_all();
  return {this, id};
}

void ClientWatch::forget(std::uint64_t id) {
  const std::lock_guard<std::mutex> lock(mutex_);
  entries_.erase(id);
}

void ClientWatch::run() {
  std::vector<std::uint64_t> ids;
  std::vector<pollfd> sockets;
  std::unique_lock<std::mutex> lock(mutex_);
  while (!stopping_) {
    if (entries_.empty()) {
      wake_.wait(lock, [this] { return stopping_ || !entries_.empty(); });
      continue;
    }
    ids.clear();
    sockets.clear();
    for (const auto& [id, entry] : entries_) {
      ids.push_back(id);
      // Only a hang-up: data from the client (a pipelined request) must not wake the poll.
      // A fired entry is not polled again (a negative descriptor is skipped by poll).
      sockets.push_back(pollfd{entry.fired ? -1 : entry.socket, POLLRDHUP, 0});
    }
    lock.unlock();
    const int ready = ::poll(sockets.data(), sockets.size(), static_cast<int>(period_.count()));
    lock.lock();
    if (ready <= 0) continue;
    // A socket forgotten meanwhile (and perhaps reused) has no entry under its id any more.
    for (std::size_t i = 0; i < sockets.size(); ++i) {
      if ((sockets[i].revents & (POLLRDHUP | POLLHUP | POLLERR | POLLNVAL)) == 0) continue;
      const auto found = entries_.find(ids[i]);
      if (found == entries_.end()) continue;
      found->second.flag->store(true);
      found->second.fired = true;
    }
  }
}

}  // namespace lang2manip
