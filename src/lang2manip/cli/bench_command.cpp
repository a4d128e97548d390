#include "lang2manip/cli/bench_commands.hpp"
#include "lang2manip/cli/commands.hpp"

namespace lang2manip {

void addBenchCommand(CLI::App& app, std::ostream& out) {
  CLI::App* bench = app.add_subcommand(
      "bench", "Benchmarks: programs that print figures (baselines run in the same process)");
  bench->require_subcommand(1);
  addBenchIkCommand(*bench, out);
  addBenchMbmCommand(*bench, out);
  addBenchKauthamCommand(*bench, out);
  addBenchTaskCommand(*bench, out);
  addBenchInstructionsCommand(*bench, out);
  addBenchFamiliesCommand(*bench, out);
}

}  // namespace lang2manip
