#include "lang2manip/core/terminal_safe_output.hpp"

#include <gtest/gtest.h>

#include <ostream>
#include <sstream>

namespace lang2manip {
namespace {

std::string filtered(const std::string& text) {
  std::ostringstream sink;
  TerminalSafeBuffer buffer(sink.rdbuf());
  std::ostream out(&buffer);
  out << text;
  out.put('!');
  out.flush();
  return sink.str();
}

TEST(TerminalSafeOutput, ControlCharactersAreShownNotObeyed) {
  EXPECT_EQ(filtered("object \"\x1b]0;owned\x07\" not found\n"), "object \"\\x1b]0;owned\\x07\" not found\n!");
  EXPECT_EQ(filtered("line\r\x7f\tend\n"), "line\\x0d\\x7f\tend\n!");
  EXPECT_EQ(filtered("caf\xc3\xa9 \xe2\x9c\x93"), "caf\xc3\xa9 \xe2\x9c\x93!") << "UTF-8 text passes";
  EXPECT_EQ(filtered(std::string("a\0b", 3)), "a\\x00b!");
}

}  // namespace
}  // namespace lang2manip
