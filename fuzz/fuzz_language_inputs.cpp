// Feed functions of the language inputs (fuzz_inputs.hpp): instructions as the offline planner
// reads them, and instruction corpora as `bench instructions` reads them.

#include <stdexcept>

#include "fuzz_inputs.hpp"
#include "lang2manip/core/error.hpp"
#include "lang2manip/language/instruction.hpp"
#include "lang2manip/language/instruction_corpus.hpp"
#include "lang2manip/language/object_descriptor.hpp"
#include "lang2manip/language/offline_task_planner.hpp"
#include "lang2manip/language/sequencer.hpp"
#include "lang2manip/model/builtin_data.hpp"
#include "lang2manip/model/kautham_problem.hpp"
#include "lang2manip/symbolic/symbolic_state.hpp"
#include "lang2manip/symbolic/task_planner.hpp"

namespace lang2manip::fuzz {
namespace {

struct Desk {
  Scene scene;
  std::vector<ObjectDescriptor> objects;
  SymbolicState state;
  SequencingOptions options;
};

const Desk& desk() {
  static const Desk loaded = [] {
    Desk d;
    d.scene = readKauthamProblem(resolveProblem("panda_desk")).scene;
    d.objects = describeObjects(d.scene);
    d.state = observeSymbolicState(d.scene);
    d.options = sequencingOptionsFor(d.scene);
    return d;
  }();
  return loaded;
}

}  // namespace

InputOutcome feedInstruction(std::string_view input) {
  const Desk& d = desk();
  try {
    const TaskSpecification specification = understandInstruction(std::string(input), d.objects);
    (void)sequenceGoals(specification, d.state, d.options);
    return InputOutcome::kAccepted;
  } catch (const PlanningError&) {
    return InputOutcome::kRejected;
  }
}

InputOutcome feedInstructionCorpus(std::string_view input) {
  try {
    const std::vector<CorpusInstruction> corpus = parseInstructionCorpus(input, "corpus");
    for (const CorpusInstruction& entry : corpus) {
      if (entry.instruction.empty() || entry.instruction.size() > kMaxCorpusInstruction || entry.line < 1) {
        throw std::logic_error("an accepted corpus line breaks its documented limits");
      }
    }
    return InputOutcome::kAccepted;
  } catch (const InputError&) {
    return InputOutcome::kRejected;
  }
}

}  // namespace lang2manip::fuzz
