#pragma once
/// Runs the real lang2manip binary for CLI tests.

#include <sys/wait.h>

#include <array>
#include <cstdio>
#include <string>

namespace lang2manip::test {

struct CliResult {
  int exitCode = -1;
  /// stdout, and stderr too when merged.
  std::string output;
};

/// Runs `lang2manip <arguments>`; stderr is merged into the output unless `mergeStderr` is false
/// (then it is discarded).
inline CliResult runCli(const std::string& arguments, bool mergeStderr = true) {
  const std::string command =
      std::string(LANG2MANIP_CLI_PATH) + " " + arguments + (mergeStderr ? " 2>&1" : " 2>/dev/null");
  CliResult result;
  FILE* pipe = ::popen(command.c_str(), "r");
  if (pipe == nullptr) return result;
  std::array<char, 4096> buffer{};
  while (std::fgets(buffer.data(), static_cast<int>(buffer.size()), pipe) != nullptr) result.output += buffer.data();
  const int status = ::pclose(pipe);
  result.exitCode = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
  return result;
}

}  // namespace lang2manip::test
