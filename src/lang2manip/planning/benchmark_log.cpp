#include "lang2manip/planning/benchmark_log.hpp"

#include <algorithm>
#include <ctime>
#include <set>

#include <unistd.h>

#include <ompl/base/PlannerStatus.h>
#include <ompl/config.h>

#include "lang2manip/planning/motion_planner.hpp"

namespace lang2manip {

const std::vector<std::string>& omplStatusNames() {
  static const std::vector<std::string> names = [] {
    std::vector<std::string> result;
    for (int i = 0; i < ompl::base::PlannerStatus::TYPE_COUNT; ++i) {
      result.push_back(ompl::base::PlannerStatus(static_cast<ompl::base::PlannerStatus::StatusType>(i)).asString());
    }
    return result;
  }();
  return names;
}

namespace {

void writePlanner(const BenchmarkPlannerRuns& planner, std::ostream& out) {
  out << planner.name << '\n';
  out << planner.common.size() << " common properties\n";
  for (const auto& [name, value] : planner.common) out << name << " = " << value << '\n';
  std::set<std::string> properties;
  for (const BenchmarkRun& run : planner.runs) {
    for (const auto& entry : run) properties.insert(entry.first);
  }
  out << properties.size() << " properties for each run\n";
  for (const std::string& property : properties) out << property << '\n';
  out << planner.runs.size() << " runs\n";
  for (const BenchmarkRun& run : planner.runs) {
    for (const std::string& property : properties) {
      const auto value = run.find(property);
      if (value != run.end()) out << value->second;
      out << "; ";
    }
    out << '\n';
  }
  out << "0 progress properties for each run\n";
  out << "0 runs\n";
  out << ".\n";
}

}  // namespace

void writeOmplBenchmarkLog(const BenchmarkExperiment& experiment, std::ostream& out) {
  out << "OMPL version " << OMPL_MAJOR_VERSION << "." << OMPL_MINOR_VERSION << "." << OMPL_PATCH_VERSION << '\n';
  out << "Experiment " << (experiment.name.empty() ? "NO_NAME" : experiment.name) << '\n';
  out << "0 experiment properties\n";
  out << "Running on " << (experiment.host.empty() ? "UNKNOWN" : experiment.host) << '\n';
  out << "Starting at " << experiment.startTime << '\n';
  out << "<<<|\n" << experiment.setupInfo << "|>>>\n";
  out << "<<<|\n" << experiment.cpuInfo << "|>>>\n";
  out << experiment.seed << " is the random seed\n";
  out << experiment.maxTime << " seconds per run\n";
  out << experiment.maxMemoryMb << " MB per run\n";
  out << experiment.runCount << " runs per planner\n";
  out << experiment.totalDuration << " seconds spent to collect the data\n";
  const std::size_t enumCount = 1 + experiment.enumTypes.size();
  out << enumCount << (enumCount == 1 ? " enum type\nstatus" : " enum types\nstatus");
  for (const std::string& name : omplStatusNames()) out << '|' << name;
  out << '\n';
  for (const auto& [name, values] : experiment.enumTypes) {
    out << name;
    for (const std::string& value : values) out << '|' << value;
    out << '\n';
  }
  out << experiment.planners.size() << " planners\n";
  for (const BenchmarkPlannerRuns& planner : experiment.planners) writePlanner(planner, out);
}

BenchmarkExperiment startBenchmarkExperiment(std::string name) {
  BenchmarkExperiment experiment;
  experiment.name = std::move(name);
  char host[256] = "UNKNOWN";
  gethostname(host, sizeof host - 1);
  experiment.host = host;
  const std::time_t now = std::time(nullptr);
  char text[64];
  std::strftime(text, sizeof text, "%Y-%b-%d %H:%M:%S", std::localtime(&now));
  experiment.startTime = text;
  return experiment;
}

BenchmarkRun invalidBenchmarkRun(bool invalidStart) {
  const auto& names = omplStatusNames();
  const auto index = std::find(names.begin(), names.end(), invalidStart ? "Invalid start" : "Invalid goal") - names.begin();
  return {{"time REAL", "0"}, {"solved BOOLEAN", "0"}, {"status ENUM", std::to_string(index)}};
}

BenchmarkRun benchmarkRunOf(const MotionPlan& plan) {
  const auto& names = omplStatusNames();
  const std::string status = plan.solved() ? "Exact solution" : "Timeout";
  const auto index = std::find(names.begin(), names.end(), status) - names.begin();
  return {{"time REAL", std::to_string(plan.statistics.planningSeconds)},
          {"solved BOOLEAN", plan.solved() ? "1" : "0"},
          {"status ENUM", std::to_string(index)},
          {"simplification time REAL", std::to_string(plan.statistics.simplifySeconds)},
          {"solution length REAL", std::to_string(plan.statistics.lengthBeforeSimplification)},
          {"simplified solution length REAL", std::to_string(plan.statistics.lengthAfterSimplification)},
          {"graph states INTEGER", std::to_string(plan.statistics.vertices)},
          {"graph motions INTEGER", std::to_string(plan.statistics.edges)},
          {"state checks INTEGER", std::to_string(plan.statistics.stateChecks)},
          {"motion checks INTEGER", std::to_string(plan.statistics.motionChecks)}};
}

}  // namespace lang2manip
