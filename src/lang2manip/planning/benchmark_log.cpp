#include "lang2manip/planning/benchmark_log.hpp"

#include <set>

#include <ompl/base/PlannerStatus.h>
#include <ompl/config.h>

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
  out << "1 enum type\nstatus";
  for (const std::string& name : omplStatusNames()) out << '|' << name;
  out << '\n';
  out << experiment.planners.size() << " planners\n";
  for (const BenchmarkPlannerRuns& planner : experiment.planners) writePlanner(planner, out);
}

}  // namespace lang2manip
