#include "lang2manip/core/terminal_safe_output.hpp"

#include <cstdio>

namespace lang2manip {
namespace {

bool isControl(unsigned char c) { return (c < 0x20 && c != '\n' && c != '\t') || c == 0x7f; }

}  // namespace

TerminalSafeBuffer::int_type TerminalSafeBuffer::overflow(int_type ch) {
  if (traits_type::eq_int_type(ch, traits_type::eof())) return traits_type::not_eof(ch);
  const char c = traits_type::to_char_type(ch);
  return xsputn(&c, 1) == 1 ? ch : traits_type::eof();
}

std::streamsize TerminalSafeBuffer::xsputn(const char* text, std::streamsize count) {
  std::streamsize start = 0;
  for (std::streamsize i = 0; i < count; ++i) {
    const auto c = static_cast<unsigned char>(text[i]);
    if (!isControl(c)) continue;
    if (target_->sputn(text + start, i - start) != i - start) return start;
    char escaped[5];
    std::snprintf(escaped, sizeof escaped, "\\x%02x", c);
    if (target_->sputn(escaped, 4) != 4) return i;
    start = i + 1;
  }
  if (target_->sputn(text + start, count - start) != count - start) return start;
  return count;
}

}  // namespace lang2manip
