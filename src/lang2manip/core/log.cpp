#include "lang2manip/core/log.hpp"

#include <atomic>
#include <iostream>
#include <mutex>

namespace lang2manip {
namespace {

std::mutex& sinkMutex() {
  static std::mutex mutex;
  return mutex;
}

void writeToStderr(LogLevel level, std::string_view message) {
  std::cerr << "lang2manip " << logLevelName(level) << ": " << message << '\n';
}

LogSink& currentSink() {
  static LogSink sink = writeToStderr;
  return sink;
}

std::atomic<LogLevel>& currentLevel() {
  static std::atomic<LogLevel> level{LogLevel::kWarn};
  return level;
}

}  // namespace

void setLogSink(LogSink sink) {
  const std::scoped_lock lock(sinkMutex());
  currentSink() = std::move(sink);
}

void setLogLevel(LogLevel level) { currentLevel() = level; }

void logMessage(LogLevel level, std::string_view message) {
  if (level < currentLevel().load()) return;
  const std::scoped_lock lock(sinkMutex());
  if (currentSink()) currentSink()(level, message);
}

std::string_view logLevelName(LogLevel level) {
  switch (level) {
    case LogLevel::kDebug: return "debug";
    case LogLevel::kInfo: return "info";
    case LogLevel::kWarn: return "warning";
    case LogLevel::kError: return "error";
  }
  return "unknown";
}

}  // namespace lang2manip
