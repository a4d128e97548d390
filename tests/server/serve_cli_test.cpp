// `lang2manip serve` as users start it: the real program in the background, stopped by SIGTERM.

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <chrono>
#include <csignal>
#include <cstdlib>
#include <regex>
#include <thread>
#include <utility>

#include "cli/cli_run.hpp"
#include "server/api_test_server.hpp"
#include "test_paths.hpp"

namespace lang2manip {
namespace {

using ::testing::HasSubstr;

/// A `lang2manip serve` process writing to a log file.
class ServeProcess {
 public:
  ServeProcess(const std::filesystem::path& directory, const std::string& arguments, const std::string& environment = "")
      : log_(directory / "serve.log") {
    const std::filesystem::path pidFile = directory / "serve.pid";
    const std::string command = environment + " " + LANG2MANIP_CLI_PATH + " serve " + arguments + " > " + log_.string() +
                                " 2>&1 & echo $! > " + pidFile.string();
    EXPECT_EQ(std::system(command.c_str()), 0);
    pid_ = std::stoi(test::readFileText(pidFile));
  }
  ~ServeProcess() { stop(); }

  /// The port it prints, waiting for it (0 when it never does).
  int port() const {
    const std::regex serving("serving on http://[^:]+:([0-9]+)/");
    for (int i = 0; i < 500; ++i) {
      std::smatch match;
      const std::string text = log();
      if (std::regex_search(text, match, serving)) return std::stoi(match[1].str());
      std::this_thread::sleep_for(std::chrono::milliseconds(20));
    }
    return 0;
  }
  void stop() {
    if (pid_ > 0) ::kill(pid_, SIGTERM);
    for (int i = 0; pid_ > 0 && i < 500 && ::kill(pid_, 0) == 0; ++i) std::this_thread::sleep_for(std::chrono::milliseconds(20));
    pid_ = 0;
  }
  [[nodiscard]] std::string log() const { return test::readFileText(log_); }

 private:
  std::filesystem::path log_;
  int pid_ = 0;
};

TEST(ServeCli, ServesUntilSigtermAndStopsCleanly) {
  const test::TempDirectory temporary;
  ServeProcess serve(temporary.path(), "--port 0", "LANG2MANIP_TOKEN=from-environment");
  const int port = serve.port();
  ASSERT_GT(port, 0) << serve.log();
  httplib::Client client("127.0.0.1", port);
  const auto refused = client.Get("/api/runs");
  ASSERT_TRUE(refused);
  EXPECT_EQ(refused->status, 401) << "the token comes from LANG2MANIP_TOKEN";
  const auto runs = client.Get("/api/runs", {{"Authorization", "Bearer from-environment"}});
  ASSERT_TRUE(runs);
  EXPECT_EQ(runs->status, 200);
  serve.stop();
  EXPECT_THAT(serve.log(), HasSubstr("server stopped"));
}

TEST(ServeCli, BadOptionsExitWithAMessage) {
  const std::pair<const char*, const char*> refused[] = {
      {"--port 70000", "--port 70000"},
      {"--port 0 --viewer /nonexistent-viewer", "no index.html"},
      {"--port 0 --data-root /nonexistent-root", "--data-root"},
      {"--port 0 --max-connections 1", "connections 2 to 4096"},
      {"--port 0 --max-request-seconds 0", "--max-request-seconds 0: expected more than 0"},
  };
  for (const auto& [arguments, message] : refused) {
    const test::RunResult result = test::run(std::string("serve ") + arguments);
    EXPECT_EQ(result.exitCode, 1) << arguments;
    EXPECT_THAT(result.output, HasSubstr(message)) << arguments;
  }
  const test::RunResult problem = test::run("serve nosuch.xml --port 0", true, "timeout 20");
  EXPECT_EQ(problem.exitCode, 1);
  EXPECT_THAT(problem.output, HasSubstr("PROBLEM nosuch.xml"));
  EXPECT_THAT(problem.output, ::testing::Not(HasSubstr("serving on")));
  const test::RunResult open = test::run("serve --host 0.0.0.0 --port 0", true, "env -u LANG2MANIP_TOKEN timeout 20");
  EXPECT_EQ(open.exitCode, 1) << open.output;
  EXPECT_THAT(open.output, HasSubstr("without a token would let anyone"));
  EXPECT_THAT(open.output, HasSubstr("--insecure"));
  EXPECT_THAT(open.output, ::testing::Not(HasSubstr("serving on")));
}

TEST(ServeCli, ASecondServeOnAPortInUseExitsWithAMessage) {
  const test::TempDirectory temporary;
  ServeProcess first(temporary.path(), "--port 0");
  const int port = first.port();
  ASSERT_GT(port, 0) << first.log();
  // timeout: a second server that starts would serve until killed.
  const test::RunResult second = test::run("serve --port " + std::to_string(port), true, "timeout 20");
  EXPECT_EQ(second.exitCode, 1);
  EXPECT_THAT(second.output, HasSubstr("address in use"));
}

TEST(BenchApiCli, HundredConcurrentClientsWithoutAnError) {
  const test::RunResult result = test::run("bench api --clients 100 --solves 1 --baseline-solves 3 --json", false);
  ASSERT_EQ(result.exitCode, 0) << result.output;
  const nlohmann::json report = nlohmann::json::parse(result.output);
  EXPECT_EQ(report["errors"], 0);
  EXPECT_EQ(report["api_solve_concurrent"]["count"], 100);
  EXPECT_GT(report["api_overhead_ratio"].get<double>(), 0.0);
  EXPECT_EQ(report["api_get_path_one_client"]["count"], 3);
  EXPECT_GT(report["api_get_path_one_client"]["median_ms"].get<double>(), 0.0);
}

TEST(BenchApiCli, ALegitimateClientIsServedUnderEveryAttack) {
  const test::RunResult result = test::run("bench api-attacks --probes 3 --attackers 8 --json", false);
  ASSERT_EQ(result.exitCode, 0) << result.output;
  const nlohmann::json report = nlohmann::json::parse(result.output);
  for (const char* attack : {"none", "header_flood", "slow_clients", "body_flood", "abandoned_solves"}) {
    ASSERT_TRUE(report.contains(attack)) << attack;
    EXPECT_EQ(report[attack]["failures"], 0) << attack;
    EXPECT_GT(report[attack]["health_median_ms"].get<double>(), 0.0) << attack;
  }
  EXPECT_EQ(report["none"]["health_ratio"], 1.0);
  const test::RunResult bad = test::run("bench api-attacks --probes 1");
  EXPECT_EQ(bad.exitCode, 1);
  EXPECT_THAT(bad.output, HasSubstr("--probes must be 3 to 10000"));
}

}  // namespace
}  // namespace lang2manip
