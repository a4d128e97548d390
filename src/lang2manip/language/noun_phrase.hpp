#pragma once
/// @file Noun phrases of an instruction (internal to the language module): reading them from
/// words ("the two small red blocks", "it", "the other one", "all the markers") and grounding
/// them to scene objects through their descriptors, with what was said before (the discourse).

#include <cstddef>
#include <optional>
#include <string>
#include <vector>

#include "lang2manip/language/object_descriptor.hpp"
#include "lang2manip/symbolic/action.hpp"
#include "lang2manip/language/words.hpp"

namespace lang2manip::language_detail {

/// Throws PlanningError: could not ground "<words>": <why>; try an LLM backend with --llm.
[[noreturn]] void throwGroundingError(const std::string& words, const std::string& why);

enum class Quantity { kDefinite, kIndefinite, kAll, kExactly };
enum class Pronoun { kNone, kIt, kThem };
/// Superlatives of size: volume (big, small), height (tall, short) and length (long).
enum class SizeWord { kNone, kBig, kSmall, kTall, kShort, kLong };
enum class PlaceWord { kNone, kLeft, kRight, kNear, kFar };
/// Where an ordinal counts from ("the second block from the left"); top is far from the robot.
enum class RankFrom { kLeft, kRight, kTop, kBottom };
/// NounPhrase::rank of "the middle one" and of "the last one".
inline constexpr int kMiddleRank = -2;
inline constexpr int kLastRank = -1;

/// The objects a noun names ("markers" -> every marker) and whether it was plural.
struct NounMatch {
  std::vector<std::string> objects;
  bool plural = false;
  /// True when the noun came from a neighbour in a list ("the red [block] and the blue block").
  bool borrowed = false;
};

struct NounPhrase;

/// What follows a noun to pick among its objects: "closest to the holder", "farthest from the
/// robot's base", "to the left of the marker", "next to the eraser", "between the bowl and the
/// box" (two references), "with the same colour as the bowl".
struct NounModifier {
  enum class Kind { kNearestTo, kFarthestFrom, kRelation, kBetween, kSameAs };
  Kind kind = Kind::kRelation;
  /// For kRelation: left_of, right_of, in_front_of, behind or next_to.
  SpatialRelation relation = SpatialRelation::kNextTo;
  /// The object the modifier refers to (one phrase; two for kBetween), empty when it is the robot
  /// ("the robot", "you": the origin of its base frame).
  std::vector<NounPhrase> reference;
  /// For kSameAs: what is the same, "colour", "shape", "size" or "kind".
  std::string property;
};

/// A noun phrase as read, before grounding.
struct NounPhrase {
  std::size_t begin = 0;
  std::size_t end = 0;
  std::string text;
  Quantity quantity = Quantity::kDefinite;
  int count = 0;
  bool other = false;
  /// "the same bowl": the one of its noun mentioned last (as a target, the latest target first).
  bool same = false;
  bool everything = false;
  Pronoun pronoun = Pronoun::kNone;
  std::vector<std::string> colours;
  SizeWord size = SizeWord::kNone;
  PlaceWord place = PlaceWord::kNone;
  std::optional<NounMatch> noun;
  /// "one"/"ones" stands for the noun said last.
  bool one = false;
  /// A determiner or adjectives followed by words that name no object ("the cup").
  bool unknownNoun = false;
  /// "movable": only objects that can be picked.
  bool movableOnly = false;
  /// Shape words ("cylindrical", "box-shaped"): the shapes it may have (ObjectDescriptor::shape).
  std::vector<std::string> shapes;
  std::optional<NounModifier> modifier;
  /// "the second block from the left": its 1-based rank counted from `rankFrom` (kLastRank,
  /// kMiddleRank; 0 when none), and whether "from ..." was said (else counted from the left).
  int rank = 0;
  RankFrom rankFrom = RankFrom::kLeft;
  bool rankFromGiven = false;
  /// "everything except the holder", "all objects but the marker": left out of what it names.
  std::vector<NounPhrase> except;

  [[nodiscard]] bool isPlural() const;
};

/// What was said before, for pronouns and "the other one".
struct Discourse {
  /// The objects acted on by the latest step.
  std::vector<std::string> lastObjects;
  /// The target of the latest relation.
  std::string lastTarget;
  /// Every object mentioned so far, in order.
  std::vector<std::string> mentioned;
  /// The objects the latest noun of an object acted on, and of a target, named before
  /// adjectives narrowed them: "one" stands for the noun said last in the same role.
  std::vector<std::string> lastObjectNoun;
  std::vector<std::string> lastTargetNoun;
  /// The objects the modifiers of the current step's objects name ("with the same colour as the
  /// bowl", "next to the box"): a target "it" of the same step means them first ("... into it").
  std::vector<std::string> stepReferences;

  void mention(const std::vector<std::string>& objects);
};

/// How far (m) an object may stand from the segment between two others to be "between" them, and
/// how much closer than the next it must be to be the one meant.
inline constexpr double kBetweenWidth = 0.10;
inline constexpr double kClearlyCloser = 0.02;

class NounPhraseReader {
 public:
  explicit NounPhraseReader(const std::vector<ObjectDescriptor>& objects);

  /// The noun phrase starting at words[at], or nullopt when none starts there.
  [[nodiscard]] std::optional<NounPhrase> read(const Words& words, std::size_t at) const;
  /// The length of an exception phrase at words[at] ("except", "but", "other than", "apart
  /// from", "excluding"); 0 when none.
  [[nodiscard]] static std::size_t exceptionWords(const Words& words, std::size_t at);
  /// The length of a negated relative clause at words[at] ("that is not", "which isn't"); 0 when
  /// none. What follows names objects left out.
  [[nodiscard]] static std::size_t negatedClauseWords(const Words& words, std::size_t at);
  /// A list "A, B and C" starting at words[at] (empty when none); nouns left out are borrowed
  /// from a neighbour ("the red and the blue block").
  [[nodiscard]] std::vector<NounPhrase> readList(const Words& words, std::size_t at) const;

  /// The objects `phrase` names. `asTarget`: it is the target of a relation (pronouns then
  /// prefer the latest target); `actedOn`: the objects of the same step, which a target pronoun
  /// does not refer to; `excluded`: objects it cannot mean (where the step puts them: "both",
  /// "the largest object" never include the destination). Throws PlanningError when it names no
  /// object or is ambiguous.
  [[nodiscard]] std::vector<std::string> ground(const NounPhrase& phrase, const Discourse& discourse,
                                                bool asTarget,
                                                const std::vector<std::string>& actedOn,
                                                bool preferContainer = false,
                                                const std::vector<std::string>& excluded = {}) const;

  [[nodiscard]] const ObjectDescriptor& descriptor(const std::string& name) const;
  [[nodiscard]] const std::vector<ObjectDescriptor>& objects() const { return objects_; }
  /// "marker, eraser, holder, desk".
  [[nodiscard]] std::string objectList() const;

 private:
  struct NounEntry {
    Words words;
    std::string object;
    int tier = 0;
  };

  [[nodiscard]] std::optional<NounMatch> matchNoun(const Words& words, std::size_t at,
                                                   std::size_t& length) const;
  [[nodiscard]] std::size_t readDeterminer(const Words& words, std::size_t at,
                                           NounPhrase& phrase) const;
  /// True when words[at] is an adjective and a noun follows the adjectives there ("red block"
  /// reads as colour + noun even when an object is named "red_block").
  [[nodiscard]] bool adjectiveBeforeNoun(const Words& words, std::size_t at) const;
  [[nodiscard]] bool readAdjective(const Words& words, std::size_t& at, NounPhrase& phrase) const;
  [[nodiscard]] std::vector<std::string> candidates(const NounPhrase& phrase,
                                                    const Discourse& discourse,
                                                    bool asTarget) const;
  [[nodiscard]] std::vector<std::string> groundPronoun(const NounPhrase& phrase,
                                                       const Discourse& discourse, bool asTarget,
                                                       const std::vector<std::string>& actedOn,
                                                       bool preferContainer) const;
  [[nodiscard]] std::vector<std::string> narrow(const NounPhrase& phrase,
                                                std::vector<std::string> names) const;
  /// Reads a modifier after the noun at words[at] into `phrase`; the position after it.
  [[nodiscard]] std::size_t readModifier(const Words& words, std::size_t at, NounPhrase& phrase) const;
  /// "from the left" (and the like) after an ordinal at words[at] into `phrase`; the position after it.
  [[nodiscard]] static std::size_t readRankFrom(const Words& words, std::size_t at, NounPhrase& phrase);
  /// The object of rank `phrase.rank` among `names` counted from `phrase.rankFrom`; throws
  /// PlanningError when there are too few, no middle one, or an ordinal other than "middle" says
  /// not where it counts from ("the third object").
  [[nodiscard]] std::vector<std::string> ranked(const NounPhrase& phrase, std::vector<std::string> names) const;
  /// True when a singular phrase without superlative could name several objects.
  [[nodiscard]] bool headIsAmbiguous(const NounPhrase& phrase) const;
  [[nodiscard]] std::vector<std::string> applyModifier(const NounPhrase& phrase, std::vector<std::string> names,
                                                       const Discourse& discourse) const;
  /// "to its left (before)", "in front of it" at words[p] into `phrase`: a relation to what "it"
  /// means; the position after it, or 0 when none is there.
  [[nodiscard]] static std::size_t readBesidePronoun(const Words& words, std::size_t p, NounPhrase& phrase, bool selects);
  /// "between X and Y", "with the same colour as X" at words[p] into `phrase`; the position after
  /// it, or 0 when neither is there.
  [[nodiscard]] std::size_t readBetweenOrSameAs(const Words& words, std::size_t p, NounPhrase& phrase, bool selects) const;
  /// The one of `names` (all when plural) between the two references, or with the reference's property.
  [[nodiscard]] std::vector<std::string> between(const NounPhrase& phrase, std::vector<std::string> names, const Discourse& discourse) const;
  [[nodiscard]] std::vector<std::string> sameAs(const NounPhrase& phrase, std::vector<std::string> names, const Discourse& discourse) const;
  [[nodiscard]] std::string describe(const std::vector<std::string>& names) const;

  std::vector<ObjectDescriptor> objects_;
  std::vector<NounEntry> nouns_;
};

}  // namespace lang2manip::language_detail
