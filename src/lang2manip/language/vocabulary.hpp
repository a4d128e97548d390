#pragma once
/// @file The fixed English vocabulary of the offline planner (internal to the language module):
/// verbs, relation phrases, directions, units, filler and sequencing words. Every table is
/// matched longest-phrase-first against the words of an instruction.

#include <cstddef>
#include <optional>
#include <set>
#include <string>
#include <vector>

#include "lang2manip/core/types.hpp"
#include "lang2manip/language/words.hpp"
#include "lang2manip/symbolic/action.hpp"

namespace lang2manip::vocabulary {

/// What a verb can ask for; a verb may allow several (e.g. "move").
struct Verb {
  std::string lemma;
  bool places = false;     ///< with a relation: put X in/on/next to Y
  bool picks = false;      ///< without a relation: hold X
  bool pushes = false;     ///< with a direction: displace X
  bool goesHome = false;   ///< "go home", "move to the home position"
  bool stacks = false;     ///< "stack the blocks"
  bool putsDown = false;   ///< "put down X", "drop X": on the support when no relation is given
  bool nudges = false;     ///< a small default push distance when none is given
  bool keeps = false;      ///< "keep X on Y", "leave X where it is": a condition, not a goal
  bool handsOver = false;  ///< "hand me X", "give X to me": held out at the handover position
  bool swaps = false;      ///< "swap X and Y": each where the other stood
  bool turns = false;      ///< "turn X by 90 degrees", "turn X to face Y"
  bool points = false;     ///< "point X at Y", "orient X toward Y"
  bool replaces = false;   ///< "replace Y with X": X where Y stood
  bool fills = false;      ///< "fill Y with X": X in Y
  bool summarizes = false; ///< "tidy up: ...": names the task the other steps spell out
};

struct VerbMatch {
  Verb verb;
  std::size_t length = 0;
};

/// The longest verb phrase at words[at] ("pick up", "put down", "push").
std::optional<VerbMatch> matchVerb(const Words& words, std::size_t at);
/// Every word of the vocabulary's phrases (verbs, relations, directions, units, fillers, sequencing
/// words, home and robot phrases): what a typo is not.
std::set<std::string> knownWords();
/// The words of the verb phrases ("pick", "up", "put", ...): what a typo may be of.
std::vector<std::string> verbWords();
/// Every verb lemma, for error messages.
std::vector<std::string> verbLemmas();

/// A relation phrase; `byTargetRole` for "to" (in a container, on a support, next to others).
struct RelationMatch {
  std::optional<SpatialRelation> relation;
  bool byTargetRole = false;
  std::size_t length = 0;
};
/// The longest relation phrase at words[at] ("on top of", "to the left of", "into").
std::optional<RelationMatch> matchRelation(const Words& words, std::size_t at);

/// A direction of motion in the robot's base frame (x forward, y left).
struct DirectionMatch {
  Vector3 direction = Vector3::Zero();
  std::size_t length = 0;
};
/// The longest direction phrase at words[at] ("to the left", "forward", "towards the robot").
std::optional<DirectionMatch> matchDirection(const Words& words, std::size_t at);

/// A length: a number and a unit ("5 cm", "2.5 centimetres", "30 mm").
struct LengthMatch {
  double metres = 0.0;
  std::size_t length = 0;
};
std::optional<LengthMatch> matchLength(const Words& words, std::size_t at);
/// The gap between two objects' boxes that a vague amount before a side relation means
/// (SpatialOptions::littleGap, lotGap: stated in the observation's conventions).
struct MagnitudeMatch {
  double gap = 0.0;
  std::size_t length = 0;
};
/// A vague amount at words[at] ("a little", "slightly", "a bit", "a lot", "far", "well").
std::optional<MagnitudeMatch> matchMagnitude(const Words& words, std::size_t at);

/// 1 when words[at] is an approximation ("about", "roughly", "around", ...) before a number, else 0.
std::size_t matchApproximation(const Words& words, std::size_t at);

/// "a bit", "a little", "slightly", "a little bit": a small amount.
std::optional<std::size_t> matchSmallAmount(const Words& words, std::size_t at);
/// The distance "a bit" and "nudge" stand for, metres.
inline constexpr double kSmallAmount = 0.02;

/// Words that carry no meaning for the plan ("please", "could you", "carefully"); removed first.
std::optional<std::size_t> matchFiller(const Words& words, std::size_t at);

/// Words that separate steps ("then", "after that", "and then", "finally").
std::optional<std::size_t> matchSequenceWord(const Words& words, std::size_t at);
/// Step words that separate only at the start of a step ("first", "next", "second").
std::optional<std::size_t> matchStepOrdinal(const Words& words, std::size_t at);

/// Words the offline planner refuses to guess about (negation, exceptions, conditions).
bool isRefusedWord(const std::string& word);
/// Words that start a question ("what", "where", "is").
bool isQuestionWord(const std::string& word);

/// "home" phrases after go/return/move: "home", "back home", "to the home position", "the arm
/// to its home pose"; the configuration is always "home".
std::optional<std::size_t> matchHome(const Words& words, std::size_t at);

}  // namespace lang2manip::vocabulary
