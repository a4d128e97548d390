#pragma once
/// @file Instruction understanding for the offline planner: plain English over a scene's
/// objects ("could you put the marker and the eraser in the holder, then go home") into ordered
/// goals, requested grasps and motion planners. Deterministic; an instruction it cannot ground
/// is an error naming the words, never a guess.

#include <map>
#include <string>
#include <vector>

#include "lang2manip/language/object_descriptor.hpp"
#include "lang2manip/symbolic/action.hpp"

namespace lang2manip {

/// What an instruction asks for.
struct TaskSpecification {
  /// The final state the instruction asks for, in the order it gives it. A step that a later
  /// one undoes is not a goal: "pick up the marker and put it in the holder" gives "marker in
  /// holder" only (holding is superseded by where the object goes; a placement by a later
  /// placement or pick of the same object; a configuration by anything the arm does after).
  std::vector<Goal> goals;
  /// Every step the instruction states, in its order (goals plus the steps later ones undo:
  /// holding the marker, going home first): what the plan goes through. Empty = the goals.
  std::vector<Goal> steps;
  /// object -> the grasp the instruction asks for ("with a side grasp", "from the top").
  std::map<std::string, GraspDirection> grasps;
  /// object -> the motion planner for the actions on it ("using RRT*" -> "RRTstar"); the key ""
  /// is for moves to a named configuration ("go home with PRM").
  std::map<std::string, std::string> planners;
  /// The planner for every other action ("use PRM for everything"); empty = the default.
  std::string defaultPlanner;
  /// What the instruction says must stay as it is ("keep the marker on the desk": a relation;
  /// "leave the eraser where it is": a zero displacement). Not goals: an instruction whose goals
  /// move a kept object is refused as contradicting itself.
  std::vector<Goal> kept;
  /// True when the instruction orders its steps ("first ..., then ...", "after that", "finally"):
  /// the plan keeps that order; otherwise a repair may change it.
  bool orderGiven = false;
  /// The typos it read as other words ("read \"markr\" as \"marker\""), empty when none.
  std::string corrections{};
};

/// Understands `text` over `objects` (see describeObjects()).
///
/// Verbs: put, place, set, lay, move, insert, drop, position, bring, transfer, return, pick up,
/// grab, grasp, take, get, lift, hold, push, slide, shove, shift, nudge, stack, go/return home.
/// Objects by name, kind and its synonyms, colour, size (big/small/largest/smallest), place
/// (left/rightmost, nearest/farthest), plurals, "all", "every", "both", "the two", "the other
/// (one)", "another", "it", "them", "this", "that". Relations: in/into/inside, on/onto/on top
/// of, next to/beside/near, (to the) left/right of, in front of, behind, "N cm to the left of",
/// "to" (in a container, on a support, next to anything else), "there". Displacements: "N cm to
/// the left/right/forward/back", "a bit to the left" (2 cm), nudge (2 cm unless told).
/// Steps joined by "and", commas, "then", "after that", "first ... then", "finally"; a step
/// without a verb repeats the previous one ("put the marker in the holder, then the eraser"), as
/// do "do the same with", "same for" and "repeat with"; a stranded "in"/"on" ("then put the
/// eraser in") means the latest target. Sources ("from the desk", "out of the holder") must name
/// an object and are otherwise implied by the scene.
/// Politeness and filler ("could you please", "kindly", "I'd like you to") are ignored. A typo of
/// an object's noun, a colour, a verb or a region word is read as that word and stated
/// (TaskSpecification::corrections); one as close to two words is refused.
/// "Stack the blocks" stacks the largest at the bottom; "stack A, B and C" puts A at the bottom.
///
/// Throws PlanningError naming the exact words it could not ground, with the reason (no object
/// matches, ambiguous between named candidates, unknown verb or planner, negation, a question),
/// e.g. `could not ground "the cup": no object matches (objects: marker, eraser, holder,
/// desk); try an LLM backend with --llm`.
TaskSpecification understandInstruction(const std::string& text,
                                        const std::vector<ObjectDescriptor>& objects);

}  // namespace lang2manip
