#pragma once
/// @file One step of an instruction ("put the marker and the eraser in the holder with a side
/// grasp") into goals (internal to the language module).

#include <optional>
#include <string>
#include <vector>

#include "lang2manip/language/instruction.hpp"
#include "lang2manip/language/noun_phrase.hpp"
#include "lang2manip/language/vocabulary.hpp"

namespace lang2manip::language_detail {

/// Grasp and planner phrases found in a step, removed from its words before parsing.
struct StepModifiers {
  std::optional<GraspDirection> grasp;
  std::string planner;
  /// "for everything", or a step that only names a planner ("use PRM").
  bool plannerForAll = false;
};

/// Removes grasp and planner phrases from `words`; throws PlanningError for a planner phrase
/// naming an unknown planner.
StepModifiers extractModifiers(Words& words);

/// A relation with its target, remembered for "there".
struct RelationSpec {
  SpatialRelation relation = SpatialRelation::kOn;
  std::string target;
  std::optional<double> distance;
  /// For on: the region of the target's top ("in the far left corner of the table").
  std::optional<SurfaceRegion> region{};
};

/// An arrangement phrase ("in an evenly spaced horizontal line", "in a triangle") and the places
/// read after it.
struct ShapePhrase {
  ArrangementShape shape = ArrangementShape::kLine;
  /// A line's named direction (base frame): "horizontal" and "row" +y, "vertical" and "column" +x.
  std::optional<Vector3> direction;
  bool diagonal = false;
  bool evenly = false;
  /// "10 cm apart": the spacing of neighbouring centres, metres.
  std::optional<double> spacing;
  std::size_t length = 0;
  /// Read after the shape: the region its centre is in, what it goes around, its support.
  std::optional<SurfaceRegion> region{};
  std::string around{};
  std::string support{};
  /// A line "between X and Y": the two objects it runs between.
  std::vector<std::string> between{};
};

/// The shape phrase at words[at] (after "in", "into", "as", "forming"), or nullopt.
std::optional<ShapePhrase> matchShapePhrase(const Words& words, std::size_t at);

/// Parses the steps of one instruction in order, adding goals to a TaskSpecification.
class StepParser {
 public:
  StepParser(const NounPhraseReader& reader, TaskSpecification& specification)
      : reader_(reader), specification_(specification) {}

  /// The step in verb-first order when it is said another way: "make X point at Y", "have X and
  /// Y trade places" (causatives), "I want X in Y" (a wish; "I want X" alone: a handover), "X and
  /// Y go in Z", "X should be on Y" (subject first); nullopt otherwise.
  [[nodiscard]] std::optional<Words> inVerbFirstOrder(const Words& words) const;
  /// "make a circle with the blocks", "form a triangle out of X, Y and Z": "put <objects> in a
  /// <shape>"; nullopt when the step is not said so.
  [[nodiscard]] std::optional<Words> inArrangementOrder(const Words& words) const;
  /// "spread (out) the blocks (out)", "scatter X": "put X spread out"; "line up the blocks
  /// (along the near edge, horizontally, in a column)": "put X in a line ..."; nullopt otherwise.
  [[nodiscard]] std::optional<Words> spreadOrLinedUp(const Words& words) const;
  /// Parses one step (words without fillers, sequencing words and modifiers).
  void parse(const Words& words, const StepModifiers& modifiers);

  /// Length of "do the same with" / "same for" / "repeat with" at words[at]; 0 when absent.
  static std::size_t sameAs(const Words& words, std::size_t at);

 private:
  struct Step;

  /// The verb at the start, or the previous step's verb for a step that starts with an object.
  void readVerb(Step& step);
  /// What follows the verb: home, or objects and where they go.
  void parsePredicate(Step& step);
  void parseSameAs(Step& step, std::size_t length);
  void parseHome(Step& step);
  /// "keep X on Y", "leave X where it is": conditions (TaskSpecification::kept), not goals.
  void parseKeep(Step& step);
  /// "hand me X", "give X to the user": X held out at handoverToolPosition().
  void parseHandOver(Step& step);
  /// "swap X and Y", "exchange the places of X and Y": each where the other stood.
  void parseSwap(Step& step);
  /// "replace Y with X": X where Y stood (Y set aside).
  void parseReplace(Step& step);
  /// "fill Y with X and Z": X and Z in Y.
  void parseFill(Step& step);
  /// True when the step hands its objects to a person ("bring me X", "bring X over to me").
  [[nodiscard]] bool handsToPerson(const Step& step) const;
  /// "turn X by 90 degrees clockwise", "rotate X a quarter turn", "turn X to face Y".
  void parseTurn(Step& step);
  /// "give X a quarter turn", "give it a 90 degree turn to the left" after the objects: turned
  /// goals; false when no turn follows.
  bool parseGivenTurn(Step& step);
  /// Turned goals by `angle` (rad, counter-clockwise) for the step's objects; a turn of zero or a
  /// full turn is refused.
  void addTurnGoals(const Step& step, double angle);
  /// "point X at Y", "orient X toward Y", "point X forward", "align X with Y".
  void parsePoint(Step& step);
  /// Facing goals for the step's objects: pointing at `target`, or, when it is empty, with the
  /// long side along the base-frame yaw `heading`.
  void addFacingGoals(const Step& step, const std::string& target, double heading);
  /// "... at/toward/to face Y" after the objects: facing goals; false when absent. After a turn
  /// verb a bare "to"/"at" is not read as pointing ("turn it to the left").
  bool parsePointing(Step& step, bool afterTurn);
  /// "... where Y is", "... in the place of Y" after the objects: an at_position goal; false
  /// when absent.
  bool parseWhereStands(Step& step);
  /// "put it back", "put it back down where it was" (ending the step): at_position goals at
  /// where the objects stand now; false when absent.
  bool parsePutBack(Step& step);
  /// "... between X and Y": an at_position goal halfway between their centres; "... halfway to X":
  /// halfway between where the object stands and X, on its support; false when absent.
  bool parseBetween(Step& step);
  /// "... to the eraser's place": an at_position goal; false when absent.
  bool parsePossessivePlace(Step& step);
  /// Goal: `object` stands where `owner` stands now (its footprint centred on the owner's).
  void addPlaceGoal(const std::string& object, const std::string& owner);
  void parseObjects(Step& step);
  /// One or more relation phrases in a row; false when none.
  bool parseRelations(Step& step);
  bool parseRelation(Step& step);
  /// "each other" / "one another" at words[after] (after "on"): the step's objects stacked; false
  /// when absent.
  bool parseEachOther(Step& step, std::size_t after);
  /// "in the top left corner (of the table)", "to the middle", "on the bottom side", "in the
  /// corner closest to the bowl": an on goal with a region of the support's top (the support the
  /// step's objects stand on when none is named); a side of an object that is not a support is
  /// a relation beside it ("on the left side of the box": left_of). False when none follows.
  bool parseRegion(Step& step);
  /// "in the bowls with matching colours", "in the bowl of the same colour", "into the bowls by
  /// colour", "with mismatched colours", "in different corners": a goal per object of the step,
  /// chosen by a matching (assignment_steps.cpp). False when none follows.
  bool parseAssignment(Step& step);
  /// For a distributive step ("one block in each bowl", "a block per corner"): each place named
  /// after the preposition at `at` gets one object of the step, those that move least; refused
  /// when there are fewer objects than places.
  void assignOnePerPlace(Step& step, std::size_t at);
  /// Each object of the step in or on the target of (or, `different`, not of) its colour: the
  /// nearest such target, unused ones first when `different`. Refused when an object has none.
  void assignByColour(Step& step, const std::vector<std::string>& targets, bool different);
  /// Each object of the step in a corner of its own of `support`'s top: the assignment that moves
  /// them least. Refused for more than four objects; for a distributive step, each corner gets
  /// one of the objects, refused for fewer than four.
  void assignCorners(Step& step, const std::string& support);
  /// "in a horizontal line", "in a circle around the bowl", "in a triangle", "spread out", with
  /// where ("along the top edge", "in the middle", "on the table"): an arranged goal and an
  /// at_position goal per object of the step (arrangement_steps.cpp). False when none follows.
  bool parseArrangement(Step& step);
  /// The places of an arrangement after its shape: a region, "along" an edge, "around" an
  /// object, the support.
  void parseArrangementPlace(Step& step, ShapePhrase& phrase);
  /// The arranged goal of the step's objects and where each goes (arrangement_layout.hpp) on the
  /// support's reachable top; refused, naming what it needs, when no layout fits.
  void arrange(Step& step, const ShapePhrase& phrase);
  /// Adds the goal `object` `relation`.
  void addGoal(const std::string& object, const RelationSpec& relation);
  /// The support a region phrase without "of ..." is of: the one the step's first object stands
  /// on, else the only support.
  [[nodiscard]] std::string defaultRegionSupport(const Step& step) const;
  /// Gives the step's goals "on <spec.target>" without a region `spec.region` ("on the desk, in
  /// the far left corner"); false when it has none.
  bool refineGoalsOnSupport(Step& step, const RelationSpec& spec);
  /// A corner the phrase left open ("a corner", "the left corner", "the corner closest to X"):
  /// among the corners it allows that have room for the step's first object (all of them when
  /// none has), the one nearest to (or farthest from) `reference`'s centre (the robot's base when
  /// `fromRobot`), or nearest to the step's first object.
  [[nodiscard]] SurfaceRegion chooseCorner(const Step& step, SurfaceRegion corner, const std::string& support,
                                           const std::string& reference, bool fromRobot, bool farthest) const;
  /// True when `object`'s footprint fits somewhere in `region` of `support`'s reachable top clear
  /// of the objects standing there (but `object` itself and those in `leaving`, which move).
  [[nodiscard]] bool regionHasRoom(const std::string& object, const std::string& support, const SurfaceRegion& region,
                                   const std::vector<std::string>& leaving) const;
  /// True when `object` rests on top of `support` (their boxes, within 1.5 cm).
  [[nodiscard]] bool standsOn(const std::string& object, const std::string& support) const;
  bool parseDisplacement(Step& step);
  void parseWithoutPlace(Step& step);
  void parseGappedRelations(Step& step);
  /// Where the step's objects go, in any of the forms (put back, between, where another stands,
  /// relations, a displacement); false when none follows.
  bool parsePlacement(Step& step);
  /// "..., and the eraser where the marker was": more objects with their own placement.
  void parseGappedPlacements(Step& step);
  /// "... instead of on top of it", "... rather than on the desk": the alternative the step
  /// rejects, skipped.
  void skipRejectedAlternative(Step& step);
  void skipSource(Step& step);
  void finish(Step& step, const StepModifiers& modifiers);

  std::vector<std::string> groundList(Step& step, const std::vector<NounPhrase>& list);
  /// The objects the step puts things in relation to ("in the holder", "on the desk next to the
  /// box"), read ahead of its objects (after particles and a source); those not yet clear are
  /// left out.
  [[nodiscard]] std::vector<std::string> peekDestinations(const Step& step, std::size_t at) const;
  /// The objects a phrase of moved objects names; the destinations are not among them when that
  /// makes the phrase name something ("both", "the largest object").
  [[nodiscard]] std::vector<std::string> groundMoved(const NounPhrase& phrase, const std::vector<std::string>& destinations) const;
  /// `intoSomething`: "in" or "to", where "it" prefers a container.
  std::string groundTarget(Step& step, const NounPhrase& phrase, bool intoSomething);
  SpatialRelation relationByRole(const std::string& target) const;
  /// A container whose opening is at least as wide as it is deep (a bowl, tray or plate): things
  /// put "on" it go in it ("on top of" it still means its rim).
  [[nodiscard]] bool isOpenDish(const std::string& object) const;
  /// The distance of a side relation whose boxes are `gap` apart (the centre offset along the side
  /// for left_of ... behind, of the step's first object; the gap itself for next_to).
  [[nodiscard]] double gapAsDistance(const Step& step, const RelationSpec& spec, double gap) const;
  void addRelationGoals(Step& step, const RelationSpec& relation);
  /// The step's objects stacked on `base` (the lowest in `region` of its top, when given).
  void addStackGoals(Step& step, const std::optional<std::string>& base, const std::optional<SurfaceRegion>& region = {});
  [[noreturn]] void failStep(const Step& step, const std::string& why) const;

  const NounPhraseReader& reader_;
  TaskSpecification& specification_;
  Discourse discourse_;
  std::optional<vocabulary::Verb> lastVerb_;
  std::optional<RelationSpec> lastRelation_;
  /// The relation of the previous step, repeated by a step without verb and place.
  std::optional<RelationSpec> lastStepRelation_;
  /// Within a step of several clauses ("the marker on the desk and the eraser on the desk next to
  /// it"): the objects of the clause before and where the current clause's goals begin.
  std::vector<std::string> clauseBefore_;
  std::size_t clauseStart_ = 0;
};

}  // namespace lang2manip::language_detail
