#include "lang2manip/core/error.hpp"

namespace lang2manip {

std::string SourceLocation::toString() const {
  if (file.empty()) return line > 0 ? "line " + std::to_string(line) : std::string();
  return line > 0 ? file + ":" + std::to_string(line) : file;
}

namespace {
std::string prefixed(const SourceLocation& where, const std::string& message) {
  const std::string place = where.toString();
  return place.empty() ? message : place + ": " + message;
}
}  // namespace

InputError::InputError(const std::string& message) : std::runtime_error(message) {}

InputError::InputError(const SourceLocation& where, const std::string& message)
    : std::runtime_error(prefixed(where, message)), where_(where) {}

}  // namespace lang2manip
