#pragma once
/// @file Runs the real lang2manip binary for the CLI tests.

#include <array>
#include <cstdio>
#include <string>
#include <sys/wait.h>

namespace lang2manip::test {

struct RunResult {
  int exitCode = -1;
  /// stdout, and stderr too unless it was discarded.
  std::string output;
};

/// Runs `lang2manip ARGUMENTS` through the shell. `environment` is put before the binary (e.g.
/// "env -u OPENAI_API_KEY OPENAI_BASE_URL=http://..."); stderr is merged into the output or,
/// with mergeStderr false, discarded.
inline RunResult run(const std::string& arguments, bool mergeStderr = true, const std::string& environment = "") {
  const std::string command = environment + (environment.empty() ? "" : " ") + std::string(LANG2MANIP_CLI_PATH) +
                              " " + arguments + (mergeStderr ? " 2>&1" : " 2>/dev/null");
  RunResult result;
  FILE* pipe = ::popen(command.c_str(), "r");
  if (pipe == nullptr) return result;
  std::array<char, 4096> buffer{};
  while (std::fgets(buffer.data(), static_cast<int>(buffer.size()), pipe) != nullptr) result.output += buffer.data();
  const int status = ::pclose(pipe);
  result.exitCode = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
  return result;
}

}  // namespace lang2manip::test
