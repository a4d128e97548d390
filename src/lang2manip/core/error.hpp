#pragma once
/// @file Error types thrown at API boundaries for bad input.

#include <stdexcept>
#include <string>

namespace lang2manip {

/// Where in an input file a problem was found (line 0 when the parser cannot tell).
struct SourceLocation {
  std::string file;
  int line = 0;

  /// "file:line", "file", or "" when nothing is known.
  [[nodiscard]] std::string toString() const;
};

/// Bad input (a file, a model, a request, an argument). The message names what and where, in
/// the form "file:line: what is wrong".
class InputError : public std::runtime_error {
 public:
  explicit InputError(const std::string& message);
  InputError(const SourceLocation& where, const std::string& message);

  /// The location given at construction (empty file when none).
  [[nodiscard]] const SourceLocation& where() const noexcept { return where_; }

 private:
  SourceLocation where_;
};

/// A request for something lang2manip does not implement (yet); the message says what.
class NotSupportedError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

}  // namespace lang2manip
