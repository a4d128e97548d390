#pragma once
/// @file One pluggable log sink for the whole library. Library code never writes to stdout; the
/// default sink writes warnings and errors to stderr. Inner loops never log.

#include <functional>
#include <string_view>

namespace lang2manip {

enum class LogLevel { kDebug, kInfo, kWarn, kError };

/// Receives every message at or above the current level.
using LogSink = std::function<void(LogLevel, std::string_view)>;

/// Replaces the sink (an empty function silences all output). Not thread-safe against logging.
void setLogSink(LogSink sink);

/// Messages below `level` are dropped (default kWarn).
void setLogLevel(LogLevel level);

/// Sends a message to the sink when its level is enabled. Thread-safe.
void logMessage(LogLevel level, std::string_view message);

inline void logWarning(std::string_view message) { logMessage(LogLevel::kWarn, message); }
inline void logInfo(std::string_view message) { logMessage(LogLevel::kInfo, message); }

/// Name of a level ("debug", "info", "warning", "error").
std::string_view logLevelName(LogLevel level);

}  // namespace lang2manip
