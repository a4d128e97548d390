#pragma once
/// @file Internal to the server module: cancelling a request's work when its client leaves. The
/// sockets of requests being served are polled by one thread; when a peer has closed its side
/// (or the connection broke), the request's cancel flag is set, so a solve or plan whose client
/// gave up stops instead of holding a core until its time limit (as nginx ends a proxied request
/// whose client closed).

#include <chrono>
#include <condition_variable>
#include <cstdint>
#include <map>
#include <mutex>
#include <thread>

#include "lang2manip/core/stop_condition.hpp"

namespace lang2manip {

class ClientWatch {
 public:
  /// Polls every `period` while something is watched.
  explicit ClientWatch(std::chrono::milliseconds period = std::chrono::milliseconds(50));
  ~ClientWatch();
  ClientWatch(const ClientWatch&) = delete;
  ClientWatch& operator=(const ClientWatch&) = delete;

  /// Watches `socket` while it lives; the socket must stay open meanwhile.
  class Registration {
   public:
    Registration(ClientWatch* watch, std::uint64_t id) : watch_(watch), id_(id) {}
    ~Registration();
    Registration(const Registration&) = delete;
    Registration& operator=(const Registration&) = delete;

   private:
    ClientWatch* watch_;
    std::uint64_t id_;
  };

  /// Sets `flag` if the client on `socket` leaves while the registration lives; a negative
  /// socket is not watched.
  [[nodiscard]] Registration watch(int socket, CancelFlag flag);

 private:
  struct Entry {
    int socket;
    CancelFlag flag;
    bool fired = false;
  };
  void run();
  void forget(std::uint64_t id);

  std::chrono::milliseconds period_;
  std::mutex mutex_;
  std::condition_variable wake_;
  bool stopping_ = false;
  std::uint64_t nextId_ = 1;
  std::map<std::uint64_t, Entry> entries_;
  std::thread thread_;
};

}  // namespace lang2manip
