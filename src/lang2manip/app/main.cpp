#include <iostream>

#include "lang2manip/app/cli_app.hpp"
#include "lang2manip/core/terminal_safe_output.hpp"

int main(int argc, char** argv) {
  // Everything printed, logs included, passes through the filter (names from files may hold
  // escape sequences).
  lang2manip::TerminalSafeBuffer out(std::cout.rdbuf());
  lang2manip::TerminalSafeBuffer err(std::cerr.rdbuf());
  std::streambuf* const originalOut = std::cout.rdbuf(&out);
  std::streambuf* const originalErr = std::cerr.rdbuf(&err);
  const int status = lang2manip::runCli(argc, argv, std::cout, std::cerr);
  std::cout.flush();
  std::cerr.flush();
  std::cout.rdbuf(originalOut);
  std::cerr.rdbuf(originalErr);
  return status;
}
