// `run --plan FILE`: a plan document executed with no task planner, and plan files that are not
// plans for the scene.

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>

#include "cli/cli_run.hpp"
#include "test_paths.hpp"

namespace lang2manip {
namespace {

namespace fs = std::filesystem;
using nlohmann::json;
using ::testing::HasSubstr;

fs::path writePlan(const fs::path& directory, const std::string& text) {
  const fs::path file = directory / "plan-in.json";
  std::ofstream(file) << text;
  return file;
}

TEST(RunPlanCli, AGivenPlanIsExecutedAndItsGoalsVerified) {
  const test::TempDirectory temporary;
  const fs::path plan = writePlan(temporary.path(), R"({"actions": [
      {"action": "pick", "object": "eraser"},
      {"action": "place", "object": "eraser", "params": {"relation": "in", "target": "holder"}}]})");
  const test::RunResult result = test::run("run --plan " + plan.string() + " --out " + (temporary.path() / "out").string() + " --json", false);
  ASSERT_EQ(result.exitCode, 0) << result.output;
  const json report = json::parse(result.output);
  EXPECT_TRUE(report["success"].get<bool>());
  EXPECT_EQ(report["task_planner"], "plan file " + plan.string()) << report.dump(1).substr(0, 400);
  EXPECT_EQ(report["goal_source"], "plan");
}

TEST(RunPlanCli, APlansGoalStatementIsWhatIsVerified) {
  const test::TempDirectory temporary;
  const std::string actions = R"("actions": [
      {"action": "pick", "object": "eraser"},
      {"action": "place", "object": "eraser", "params": {"relation": "in", "target": "holder"}}])";
  const fs::path kept = writePlan(temporary.path(), "{" + actions + R"(, "goals": [{"kind": "relation", "object": "eraser", "relation": "in", "target": "holder"}]})");
  const test::RunResult met = test::run("run --plan " + kept.string() + " --out " + (temporary.path() / "met").string() + " --json", false);
  ASSERT_EQ(met.exitCode, 0) << met.output;
  json report = json::parse(met.output);
  EXPECT_EQ(report["goal_source"], "plan_goal_statement");
  EXPECT_THAT(report["goals"].dump(), HasSubstr("eraser in holder"));
  // A statement the plan does not make true: the run fails on that goal, it is not replaced by
  // what the actions imply.
  const fs::path wrong = writePlan(temporary.path(), "{" + actions + R"(, "goals": [{"kind": "relation", "object": "marker", "relation": "in", "target": "holder"}]})");
  const test::RunResult unmet = test::run("run --plan " + wrong.string() + " --out " + (temporary.path() / "unmet").string() + " --json", false);
  EXPECT_EQ(unmet.exitCode, 2) << unmet.output;
  report = json::parse(unmet.output);
  EXPECT_FALSE(report["success"].get<bool>());
  EXPECT_EQ(report["goal_source"], "plan_goal_statement");
  EXPECT_THAT(report["goals"].dump(), HasSubstr("marker in holder"));
}

TEST(RunPlanCli, APlanIsReadFromStandardInput) {
  const test::TempDirectory temporary;
  const fs::path plan = writePlan(temporary.path(), R"({"actions": [{"action": "pick", "object": "eraser"}]})");
  const test::RunResult result = test::run("run --json --plan - --out " + (temporary.path() / "out").string(), false, "cat " + plan.string() + " |");
  ASSERT_EQ(result.exitCode, 0) << result.output;
  EXPECT_EQ(json::parse(result.output)["task_planner"], "plan on standard input");
  const test::RunResult nothing = test::run("run --plan - --out " + (temporary.path() / "none").string(), true, "true |");
  EXPECT_EQ(nothing.exitCode, 1);
  EXPECT_THAT(nothing.output, HasSubstr("plan on standard input is empty"));
}

TEST(RunPlanCli, AGivenPlanThatCannotBeExecutedIsNotReplanned) {
  const test::TempDirectory temporary;
  const fs::path plan = writePlan(temporary.path(), R"({"actions": [{"action": "pick", "object": "eraser"},
      {"action": "place", "object": "eraser", "params": {"position": [3.0, 0.0, 0.8]}}]})");
  const test::RunResult result = test::run("run --plan " + plan.string() + " --out " + (temporary.path() / "out").string());
  EXPECT_EQ(result.exitCode, 2) << result.output;
  EXPECT_THAT(test::readFileText(temporary.path() / "out" / "report.json"), HasSubstr("round"));
}

TEST(RunPlanCli, PlanFilesThatAreNotPlansForTheSceneAreNamed) {
  const test::TempDirectory temporary;
  const std::string out = " --out " + (temporary.path() / "out").string();
  const test::RunResult unknown = test::run("run --plan " + writePlan(temporary.path(), R"({"actions": [{"action": "pick", "object": "unicorn"}]})").string() + out);
  EXPECT_EQ(unknown.exitCode, 1);
  EXPECT_THAT(unknown.output, HasSubstr("actions[0].object: unknown object \"unicorn\""));
  const test::RunResult broken = test::run("run --plan " + writePlan(temporary.path(), "[1, 2").string() + out);
  EXPECT_EQ(broken.exitCode, 1);
  EXPECT_THAT(broken.output, HasSubstr("not valid JSON"));
  const test::RunResult notPlan = test::run("run --plan " + writePlan(temporary.path(), R"({"answer": 42})").string() + out);
  EXPECT_EQ(notPlan.exitCode, 1);
  EXPECT_THAT(notPlan.output, HasSubstr("is not a plan for this scene"));
  const test::RunResult missing = test::run("run --plan /nonexistent/plan.json" + out);
  EXPECT_EQ(missing.exitCode, 1);
  EXPECT_THAT(missing.output, HasSubstr("plan file does not exist"));
  const test::RunResult directory = test::run("run --plan " + temporary.path().string() + out);
  EXPECT_THAT(directory.output, HasSubstr("is a directory"));
  const test::RunResult fixed = test::run("run --plan " + writePlan(temporary.path(), R"({"actions": [{"action": "pick", "object": "desk"}]})").string() + out);
  EXPECT_EQ(fixed.exitCode, 1) << "a plan the scene's state refuses is bad input, not a failed task";
  EXPECT_THAT(fixed.output, HasSubstr("cannot be executed in this scene:\nstep 1 (pick desk): desk is fixed and cannot be picked"));
  const test::RunResult prose = test::run("run --plan " + writePlan(temporary.path(), "Sure! {\"actions\": []}").string() + out);
  EXPECT_EQ(prose.exitCode, 1);
  EXPECT_THAT(prose.output, HasSubstr("plan-in.json: not valid JSON")) << "a plan file is JSON, not an LLM's answer";
  const test::RunResult empty = test::run("run --plan " + writePlan(temporary.path(), " \n").string() + out);
  EXPECT_THAT(empty.output, HasSubstr("is empty; expected a JSON plan document"));
  const test::RunResult llm = test::run("run --plan " + writePlan(temporary.path(), "{}").string() + " --llm openai:gpt-4o" + out);
  EXPECT_EQ(llm.exitCode, 1);
  EXPECT_THAT(llm.output, HasSubstr("give one of them"));
}

}  // namespace
}  // namespace lang2manip
