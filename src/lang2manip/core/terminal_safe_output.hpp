#pragma once
/// @file Output for terminals that text from files cannot drive: names read from problems,
/// scenes, plans and LLM answers reach messages, and a name holding an escape sequence
/// ("\x1b]0;...", "\x1b[2J") would otherwise retitle, clear or rewrite the user's terminal.

#include <streambuf>

namespace lang2manip {

/// A stream buffer that passes text on to `target` with every control character but newline and
/// tab (C0, and DEL) written as "\xHH". Installed on standard output and error by the program.
class TerminalSafeBuffer : public std::streambuf {
 public:
  explicit TerminalSafeBuffer(std::streambuf* target) : target_(target) {}

 protected:
  int_type overflow(int_type ch) override;
  std::streamsize xsputn(const char* text, std::streamsize count) override;
  int sync() override { return target_->pubsync(); }

 private:
  std::streambuf* target_;
};

}  // namespace lang2manip
