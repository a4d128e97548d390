#include "lang2manip/language/instruction.hpp"

#include <algorithm>
#include <iterator>
#include <map>

#include "lang2manip/language/clause_parser.hpp"
#include "lang2manip/language/stack_order.hpp"
#include "lang2manip/language/goal_conflicts.hpp"
#include "lang2manip/language/noun_phrase.hpp"
#include "lang2manip/language/typo_correction.hpp"
#include "lang2manip/language/vocabulary.hpp"
#include "lang2manip/symbolic/task_planner.hpp"

namespace lang2manip {
namespace {

using language_detail::throwGroundingError;

void refuseWhatCannotBeGrounded(const Words& words) {
  if (words.empty()) {
    throw PlanningError("the task is empty; say what to do, e.g. \"put the marker in the holder\"");
  }
  if (vocabulary::isQuestionWord(words.front())) {
    throwGroundingError(joinWords(words), "it is a question, not an instruction");
  }
  static const std::vector<std::string> quantifiers{"everything", "all", "every", "each", "both", "objects", "things", "items", "anything"};
  const auto afterQuantifier = [&](std::size_t at) {
    for (std::size_t back = 1; back <= 4 && back <= at; ++back) {
      if (std::find(quantifiers.begin(), quantifiers.end(), words[at - back]) != quantifiers.end()) return true;
    }
    return false;
  };
  for (std::size_t at = 0; at < words.size(); ++at) {
    // "everything except the holder": an exception to a quantifier, read by the noun phrases.
    if (language_detail::NounPhraseReader::exceptionWords(words, at) > 0 && afterQuantifier(at)) continue;
    const auto negatedClauseAt = [&](std::size_t back) {
      return back <= at && language_detail::NounPhraseReader::negatedClauseWords(words, at - back) == back + 1;
    };
    if (negatedClauseAt(1) || negatedClauseAt(2)) continue;  // "the object that is not the eraser"
    if (words[at] == "instead" && at > 0 && at + 1 < words.size() && words[at + 1] == "of") continue;  // the rejected alternative is skipped
    if (vocabulary::isRefusedWord(words[at]) ||
        (words[at] == "do" && at + 1 < words.size() && words[at + 1] == "not")) {
      throwGroundingError(words[at], "the offline planner does not follow negation, exceptions, "
                                     "alternatives or conditions");
    }
  }
}

Words withoutFillers(const Words& words) {
  Words kept;
  for (std::size_t at = 0; at < words.size();) {
    if (auto filler = vocabulary::matchFiller(words, at)) {
      at += *filler;
    } else {
      kept.push_back(words[at++]);
    }
  }
  return kept;
}

bool startsStep(const Words& words, std::size_t at) {
  return at < words.size() &&
         (vocabulary::matchVerb(words, at) || vocabulary::matchSequenceWord(words, at) ||
          vocabulary::matchStepOrdinal(words, at) ||
          language_detail::StepParser::sameAs(words, at) > 0);
}

bool endsStep(const Words& words, std::size_t at) {
  return at >= words.size() || isPunctuation(words[at]) ||
         vocabulary::matchSequenceWord(words, at);
}

/// Splits at sentence punctuation, sequencing words, and at "and" or "," before a verb.
/// The steps of `words`; `ordered` is set when a sequencing word or an ordinal joins them.
std::vector<Words> splitSteps(const Words& words, bool& ordered) {
  std::vector<Words> steps(1);
  auto split = [&steps] {
    if (!steps.back().empty()) steps.emplace_back();
  };
  for (std::size_t at = 0; at < words.size();) {
    const std::string& word = words[at];
    if (auto sequence = vocabulary::matchSequenceWord(words, at)) {
      split();
      ordered = true;
      at += *sequence;
    } else if (auto ordinal = vocabulary::matchStepOrdinal(words, at);
               ordinal && (steps.back().empty() || endsStep(words, at + *ordinal))) {
      split();
      ordered = true;
      at += *ordinal;
    } else if (word == "," && at + 1 < words.size() && words[at + 1] == "and" && (startsStep(words, at + 2) || endsStep(words, at + 2))) {
      split();  // "lift it, and put it down": a serial comma before the next step
      at += 2;
    } else if (word == "," || word == "and") {
      if (startsStep(words, at + 1) || endsStep(words, at + 1)) split();
      else steps.back().push_back(word);
      ++at;
    } else if (isPunctuation(word)) {
      split();
      ++at;
    } else {
      steps.back().push_back(words[at++]);
    }
  }
  if (steps.back().empty()) steps.pop_back();
  return steps;
}

bool involves(const Goal& goal, const std::string& object) {
  return !object.empty() && (goal.object == object || containsWord(goal.members, object));
}

/// Whether `later` is about any object `earlier` is about.
bool involvesAnyOf(const Goal& later, const Goal& earlier) {
  if (involves(later, earlier.object)) return true;
  return std::any_of(earlier.members.begin(), earlier.members.end(), [&](const std::string& member) { return involves(later, member); });
}

void checkHoldingGoals(const TaskSpecification& specification) {
  std::vector<std::string> held;
  for (std::size_t i = 0; i < specification.goals.size(); ++i) {
    const Goal& goal = specification.goals[i];
    if (goal.kind != GoalKind::kHolding && goal.kind != GoalKind::kHandedOver) continue;
    const bool superseded = std::any_of(specification.goals.begin() + static_cast<std::ptrdiff_t>(i) + 1,
                                        specification.goals.end(),
                                        [&goal](const Goal& later) { return involves(later, goal.object); });
    if (!superseded && std::find(held.begin(), held.end(), goal.object) == held.end()) {
      held.push_back(goal.object);
    }
  }
  if (held.size() > 1) {
    std::string names;
    for (const std::string& name : held) names += (names.empty() ? "" : " and ") + name;
    throw PlanningError("could not ground the task: the robot has one gripper and cannot hold " +
                        names + " at once; say where to put all but one");
  }
}

/// Whether `later` says what becomes of `earlier`'s subject, so that `earlier` is a step on the
/// way rather than part of the final state: what is held is later put somewhere (or held
/// again), an object placed somewhere is later placed elsewhere or picked up again, the arm
/// goes to a configuration and later does anything else.
bool supersedes(const Goal& later, const Goal& earlier) {
  switch (earlier.kind) {
    case GoalKind::kHolding:
    case GoalKind::kHandedOver: return involves(later, earlier.object);
    case GoalKind::kRelation:
    case GoalKind::kAtPosition:  // a turn in place keeps where it stands
    case GoalKind::kArranged:    // and the places of an arrangement are its members' goals
      return involvesAnyOf(later, earlier) && later.kind != GoalKind::kDisplaced && later.kind != GoalKind::kAtConfiguration &&
             later.kind != GoalKind::kTurned && later.kind != GoalKind::kFacing;
    case GoalKind::kTurned:
    case GoalKind::kFacing:
      return involves(later, earlier.object) && later.kind != GoalKind::kDisplaced && later.kind != GoalKind::kAtConfiguration;
    case GoalKind::kAtConfiguration: return true;
    case GoalKind::kDisplaced: return involves(later, earlier.object) && later.kind == GoalKind::kDisplaced;
  }
  return false;
}

/// The goals that describe the final state the instruction asks for: those no later goal
/// supersedes, in order ("pick up the marker and put it in the holder": marker in holder).
std::vector<Goal> finalStateGoals(const std::vector<Goal>& goals) {
  std::vector<Goal> kept;
  std::map<std::string, Vector3> displacedBefore;  // "5 cm left, then 3 cm forward": moved by both
  for (std::size_t i = 0; i < goals.size(); ++i) {
    const bool isStep = std::any_of(goals.begin() + static_cast<std::ptrdiff_t>(i) + 1, goals.end(),
                                    [&](const Goal& later) { return supersedes(later, goals[i]); });
    Goal goal = goals[i];
    if (goal.kind == GoalKind::kDisplaced) {
      const auto before = displacedBefore.find(goal.object);
      if (before != displacedBefore.end()) goal.displacement += before->second;
      displacedBefore[goal.object] = goal.displacement;
    } else if (!goal.object.empty()) {
      displacedBefore.erase(goal.object);
    }
    if (!isStep) kept.push_back(goal);
  }
  return kept;
}

}  // namespace

TaskSpecification understandInstruction(const std::string& text,
                                        const std::vector<ObjectDescriptor>& objects) {
  Words words = tokenize(text);
  TaskSpecification specification;
  specification.corrections = language_detail::correctionsText(language_detail::correctTypos(words, objects));
  refuseWhatCannotBeGrounded(words);
  const language_detail::NounPhraseReader reader(objects);
  language_detail::StepParser parser(reader, specification);
  Words said = withoutFillers(words);
  if (std::optional<Words> tower = language_detail::orderedStack(said, reader)) said = std::move(*tower);
  for (Words& step : splitSteps(said, specification.orderGiven)) {
    const language_detail::StepModifiers modifiers = language_detail::extractModifiers(step);
    parser.parse(step, modifiers);
  }
  language_detail::refuseMovingKeptObjects(specification.goals, specification.kept, text);
  if (specification.goals.empty()) {
    throwGroundingError(text, "it asks for nothing the robot could do");
  }
  checkHoldingGoals(specification);
  // A step said twice in a row ("I need the marker, hand it over") is done once.
  specification.goals.erase(std::unique(specification.goals.begin(), specification.goals.end(),
                                        [](const Goal& a, const Goal& b) { return describeGoal(a) == describeGoal(b); }),
                            specification.goals.end());
  // A turn after the object was put somewhere ("swap them, then rotate the eraser") is made there.
  for (std::size_t i = 0; i < specification.goals.size(); ++i) {
    Goal& turn = specification.goals[i];
    if (turn.kind != GoalKind::kTurned) continue;
    for (std::size_t j = i; j-- > 0;) {
      const Goal& before = specification.goals[j];
      if (before.object != turn.object) continue;
      if (before.kind == GoalKind::kAtPosition) turn.position = before.position;
      break;
    }
  }
  // The steps go through the members' places; the final state is the arrangement.
  const std::vector<Goal> all = specification.goals;
  specification.steps.clear();
  std::copy_if(all.begin(), all.end(), std::back_inserter(specification.steps), [](const Goal& goal) { return goal.kind != GoalKind::kArranged; });
  specification.goals = finalStateGoals(all);
  return specification;
}

}  // namespace lang2manip
