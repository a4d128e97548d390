#include "lang2manip/language/noun_phrase.hpp"

#include <algorithm>
#include <cmath>
#include <functional>
#include <numeric>

#include "lang2manip/language/vocabulary.hpp"
#include "lang2manip/symbolic/task_planner.hpp"

namespace lang2manip::language_detail {
namespace {

constexpr int kNameTier = 0;
constexpr int kKindTier = 1;
constexpr int kSynonymTier = 2;
constexpr int kGenericTier = 3;
/// The largest count read as a number of objects ("three blocks"); larger numbers name nothing.
constexpr double kMostCounted = 10000.0;


/// Colour words and the colour name they mean.
std::optional<std::string> colourWord(const std::string& word) {
  static const std::vector<std::pair<std::string, std::string>> aliases{
      {"gray", "grey"}, {"violet", "purple"}, {"magenta", "pink"}, {"navy", "blue"},
      {"gold", "yellow"}, {"golden", "yellow"}, {"turquoise", "cyan"}, {"teal", "cyan"}};
  if (containsWord(colourNames(), word)) return word;
  for (const auto& [alias, name] : aliases) {
    if (word == alias) return name;
  }
  return std::nullopt;
}

std::optional<SizeWord> sizeWord(const std::string& word) {
  static const std::vector<std::string> big{"big", "bigger", "biggest", "large", "larger",
                                            "largest", "huge", "giant"};
  static const std::vector<std::string> small{"small", "smaller", "smallest", "little", "tiny",
                                              "mini"};
  static const std::vector<std::string> tall{"tall", "taller", "tallest", "highest", "higher"};
  static const std::vector<std::string> low{"shortest", "lowest", "flattest", "flatter", "short", "shorter", "low", "lower", "flat"};
  static const std::vector<std::string> longer{"longest", "longer", "long"};
  if (containsWord(big, word)) return SizeWord::kBig;
  if (containsWord(small, word)) return SizeWord::kSmall;
  if (containsWord(tall, word)) return SizeWord::kTall;
  if (containsWord(low, word)) return SizeWord::kShort;
  if (containsWord(longer, word)) return SizeWord::kLong;
  return std::nullopt;
}

/// 1-based rank of an ordinal word ("second": 2), kLastRank, kMiddleRank; 0 otherwise.
int rankWord(const std::string& word) {
  static const std::vector<std::string> ordinals{"first", "second", "third", "fourth", "fifth", "sixth", "seventh", "eighth", "ninth", "tenth"};
  if (const auto it = std::find(ordinals.begin(), ordinals.end(), word); it != ordinals.end()) return static_cast<int>(it - ordinals.begin()) + 1;
  if (word == "last") return kLastRank;
  if (word == "middle" || word == "center" || word == "centre" || word == "central") return kMiddleRank;
  return 0;
}

std::optional<PlaceWord> placeWord(const std::string& word) {
  if (word == "left" || word == "leftmost") return PlaceWord::kLeft;
  if (word == "right" || word == "rightmost") return PlaceWord::kRight;
  if (word == "nearest" || word == "closest" || word == "near" || word == "closer") {
    return PlaceWord::kNear;
  }
  if (word == "farthest" || word == "furthest" || word == "far" || word == "farther") {
    return PlaceWord::kFar;
  }
  return std::nullopt;
}

bool isShadeWord(const std::string& word) {
  return word == "dark" || word == "light" || word == "bright" || word == "pale";
}

/// Words that end an unknown noun's span in an error message.
bool endsPhrase(const Words& words, std::size_t at) {
  const std::string& word = words[at];
  return isPunctuation(word) || word == "and" || word == "then" || word == "up" ||
         word == "down" || vocabulary::matchRelation(words, at) ||
         vocabulary::matchDirection(words, at) || vocabulary::matchLength(words, at) ||
         vocabulary::matchVerb(words, at);
}

}  // namespace

void throwGroundingError(const std::string& words, const std::string& why) {
  throw PlanningError("could not ground \"" + words + "\": " + why +
                      "; try an LLM backend with --llm");
}

bool NounPhrase::isPlural() const {
  if (pronoun != Pronoun::kNone) return pronoun == Pronoun::kThem;
  if (everything || quantity == Quantity::kAll) return true;
  if (quantity == Quantity::kExactly) return count != 1;
  return noun && noun->plural && !noun->borrowed;
}

void Discourse::mention(const std::vector<std::string>& objects) {
  for (const std::string& object : objects) {
    if (!containsWord(mentioned, object)) mentioned.push_back(object);
  }
}

NounPhraseReader::NounPhraseReader(const std::vector<ObjectDescriptor>& objects)
    : objects_(objects) {
  for (const ObjectDescriptor& object : objects_) {
    const Words name = nameWords(object.name);
    nouns_.push_back({name, object.name, kNameTier});
    if (const Words written = tokenize(object.name); written != name) nouns_.push_back({written, object.name, kNameTier});  // "pawnB1" as typed
    const std::string nameHead = headNoun(name);
    const bool adjective = colourWord(nameHead) || sizeWord(nameHead) || placeWord(nameHead);
    if (!nameHead.empty() && !adjective) nouns_.push_back({{nameHead}, object.name, kKindTier});
    const Words kind = nameWords(object.kind);
    if (!kind.empty()) {
      nouns_.push_back({kind, object.name, kKindTier});
      if (const std::string head = headNoun(kind); !head.empty()) nouns_.push_back({{head}, object.name, kKindTier});
    }
    for (const std::string& synonym : object.synonyms) {
      nouns_.push_back({tokenize(synonym), object.name, kSynonymTier});
    }
    if (object.role == ObjectRole::kContainer) {
      nouns_.push_back({{"container"}, object.name, kSynonymTier});
    }
    if (object.role == ObjectRole::kSupport) {
      nouns_.push_back({{"surface"}, object.name, kSynonymTier});
    }
    if (object.movable) {
      for (const char* generic : {"object", "thing", "item"}) {
        nouns_.push_back({{generic}, object.name, kGenericTier});
      }
    }
  }
}

std::optional<NounMatch> NounPhraseReader::matchNoun(const Words& words, std::size_t at,
                                                     std::size_t& length) const {
  std::size_t bestLength = 0;
  int bestTier = kGenericTier + 1;
  NounMatch match;
  for (const NounEntry& entry : nouns_) {
    const std::size_t size = entry.words.size();
    if (size == 0 || at + size > words.size()) continue;
    const bool prefix = std::equal(entry.words.begin(), entry.words.end() - 1, words.begin() + static_cast<std::ptrdiff_t>(at));
    if (!prefix) continue;
    const std::string& last = words[at + size - 1];
    const bool singular = last == entry.words.back();
    const bool plural = !singular && containsWord(singularCandidates(last), entry.words.back());
    if (!singular && !plural) continue;
    const bool better = size > bestLength || (size == bestLength && entry.tier < bestTier);
    if (better) {
      bestLength = size;
      bestTier = entry.tier;
      match = NounMatch{};
    }
    if (size == bestLength && entry.tier == bestTier && !containsWord(match.objects, entry.object)) {
      match.objects.push_back(entry.object);
      match.plural = plural;
    }
  }
  if (bestLength == 0) return std::nullopt;
  // Keep scene order whatever order the entries matched in.
  std::vector<std::string> ordered;
  for (const ObjectDescriptor& object : objects_) {
    if (containsWord(match.objects, object.name)) ordered.push_back(object.name);
  }
  match.objects = ordered;
  length = bestLength;
  return match;
}

std::size_t NounPhraseReader::readDeterminer(const Words& words, std::size_t at,
                                             NounPhrase& phrase) const {
  struct Determiner {
    Words words;
    Quantity quantity;
    int count;
    bool other;
  };
  static const std::vector<Determiner> determiners = [] {
    std::vector<Determiner> list;
    auto add = [&list](const char* text, Quantity quantity, int count = 0, bool other = false) {
      list.push_back({tokenize(text), quantity, count, other});
    };
    for (const char* text : {"the", "this", "that", "these", "those", "my", "your"}) {
      add(text, Quantity::kDefinite);
    }
    for (const char* text : {"a", "an", "any", "some", "one of the"}) add(text, Quantity::kIndefinite);
    for (const char* text : {"all", "all the", "all of the", "all of", "every", "each",
                             "each of the", "all those", "all these"}) {
      add(text, Quantity::kAll);
    }
    for (const char* text : {"both", "both the", "both of the"}) add(text, Quantity::kExactly, 2);
    add("the other", Quantity::kDefinite, 0, true);
    add("another", Quantity::kIndefinite, 0, true);
    add("the other two", Quantity::kExactly, 2, true);
    return list;
  }();
  const Determiner* best = nullptr;
  for (const Determiner& determiner : determiners) {
    if (matchesAt(words, at, determiner.words) &&
        (!best || determiner.words.size() > best->words.size())) {
      best = &determiner;
    }
  }
  std::size_t length = 0;
  if (best) {
    phrase.quantity = best->quantity;
    phrase.count = best->count;
    phrase.other = best->other;
    length = best->words.size();
  }
  if (best && best->words == Words{"the"} && matchesAt(words, at + 1, {"same"})) {
    phrase.same = true;  // "the same bowl"
    ++length;
  }
  // "the two markers", "three blocks"
  if (at + length < words.size() && phrase.quantity != Quantity::kExactly) {
    const std::optional<double> number = numberValue(words[at + length]);
    const bool unit = vocabulary::matchLength(words, at + length).has_value();
    if (number && !unit && *number == 1) {
      phrase.quantity = Quantity::kIndefinite;  // "one marker", "one of them"
      phrase.one = true;
      ++length;
    } else if (number && !unit && *number > 1 && *number <= kMostCounted && std::floor(*number) == *number) {
      phrase.quantity = Quantity::kExactly;
      phrase.count = static_cast<int>(*number);
      ++length;
    }
  }
  return length;
}

bool NounPhraseReader::adjectiveBeforeNoun(const Words& words, std::size_t at) const {
  NounPhrase scratch;
  std::size_t position = at;
  if (!readAdjective(words, position, scratch)) return false;
  while (position < words.size()) {
    std::size_t length = 0;
    if (words[position] == "one" || words[position] == "ones" || matchNoun(words, position, length)) {
      return true;
    }
    if (!readAdjective(words, position, scratch)) return false;
  }
  return false;
}

/// Shape words at words[at] ("cylindrical", "box shaped") with the shapes they allow and their
/// length; nullopt when none.
std::optional<std::pair<std::vector<std::string>, std::size_t>> shapeWords(const Words& words, std::size_t at) {
  static const std::vector<std::pair<Words, std::vector<std::string>>> table{
      {{"cylindrical"}, {"cylinder"}}, {{"tubular"}, {"cylinder"}},          {{"round"}, {"cylinder", "sphere"}},
      {{"rounded"}, {"cylinder", "sphere"}}, {{"spherical"}, {"sphere"}},     {{"ball", "shaped"}, {"sphere"}},
      {{"box", "shaped"}, {"box"}},      {{"boxy"}, {"box"}},                 {{"rectangular"}, {"box"}},
      {{"cuboid"}, {"box"}},             {{"block", "shaped"}, {"box"}},      {{"brick", "shaped"}, {"box"}},
      {{"cylinder", "shaped"}, {"cylinder"}}, {{"angular"}, {"box"}}};
  std::optional<std::pair<std::vector<std::string>, std::size_t>> best;
  for (const auto& [phrase, shapes] : table) {
    if (matchesAt(words, at, phrase) && (!best || phrase.size() > best->second)) best = std::make_pair(shapes, phrase.size());
  }
  return best;
}

bool NounPhraseReader::readAdjective(const Words& words, std::size_t& at, NounPhrase& phrase) const {
  const std::string& word = words[at];
  if (const auto shape = shapeWords(words, at)) {
    phrase.shapes = shape->first;
    at += shape->second;
    return true;
  }
  if (word == "remaining" || word == "leftover" || word == "rest") {
    phrase.other = true;  // "the remaining object": one not mentioned yet
    ++at;
    return true;
  }
  if (const int rank = rankWord(word); rank != 0 && phrase.rank == 0) {
    phrase.rank = rank;
  } else if (auto colour = colourWord(word)) {
    phrase.colours.push_back(*colour);
  } else if (auto size = sizeWord(word)) {
    phrase.size = *size;
  } else if (auto place = placeWord(word)) {
    phrase.place = *place;
  } else if (word == "movable" || word == "moveable" || word == "loose") {
    phrase.movableOnly = true;
  } else if (!(isShadeWord(word) && at + 1 < words.size() && colourWord(words[at + 1]))) {
    return false;
  }
  ++at;
  return true;
}

std::optional<NounPhrase> NounPhraseReader::read(const Words& words, std::size_t at) const {
  if (at >= words.size()) return std::nullopt;
  NounPhrase phrase;
  phrase.begin = at;
  std::size_t position = at;
  const std::string& first = words[at];
  if (first == "it" || first == "them" || first == "they") {
    phrase.pronoun = first == "it" ? Pronoun::kIt : Pronoun::kThem;
    ++position;
    if (position < words.size() && (words[position] == "both" || words[position] == "all")) {
      ++position;
    }
  } else if (first == "everything" || matchesAt(words, at, {"all", "of", "them"}) ||
             matchesAt(words, at, {"both", "of", "them"})) {
    if (first == "everything") {
      phrase.everything = true;
      phrase.quantity = Quantity::kAll;
      position += 1;
      if (position < words.size() && (words[position] == "movable" || words[position] == "moveable" || words[position] == "loose")) {
        phrase.movableOnly = true;  // "everything movable"
        ++position;
      }
    } else {
      phrase.pronoun = Pronoun::kThem;
      if (first == "both") phrase.quantity = Quantity::kExactly, phrase.count = 2;
      position += 3;
    }
  } else {
    position += readDeterminer(words, position, phrase);
    bool adjectives = false;
    std::size_t length = 0;
    while (position < words.size()) {
      if (words[position] == "one" || words[position] == "ones") {
        phrase.one = true;
        ++position;
        break;
      }
      if (adjectiveBeforeNoun(words, position)) {
        (void)readAdjective(words, position, phrase);
        adjectives = true;
        continue;
      }
      if (auto noun = matchNoun(words, position, length)) {
        phrase.noun = std::move(noun);
        position += length;
        // "the pen-like object", "the marker shaped thing": the noun before says which.
        static const std::vector<std::string> like{"like", "shaped", "looking", "style"};
        static const std::vector<std::string> generic{"object", "thing", "item", "one"};
        if (position + 1 < words.size() && containsWord(like, words[position]) && containsWord(generic, words[position + 1])) {
          position += 2;
        }
        break;
      }
      if (!readAdjective(words, position, phrase)) break;
      adjectives = true;
    }
    const bool determiner = position > at;
    if (first == "both" && phrase.noun && !phrase.noun->plural) {
      phrase.quantity = Quantity::kDefinite;  // "both the marker and the eraser"
      phrase.count = 0;
    }
    if (!phrase.noun && !phrase.one && phrase.other && !adjectives) {
      phrase.one = true;  // "the other", "another"
    }
    if (!phrase.noun && !phrase.one) {
      if (!determiner) return std::nullopt;
      const bool demonstrative = first == "this" || first == "that" || first == "these" ||
                                 first == "those";
      if (demonstrative && position == at + 1 &&
          (position >= words.size() || endsPhrase(words, position))) {
        phrase.pronoun = (first == "this" || first == "that") ? Pronoun::kIt : Pronoun::kThem;
        phrase.end = position;
        phrase.text = first;
        return phrase;
      }
      if (phrase.quantity == Quantity::kAll && !adjectives &&
          (position >= words.size() || endsPhrase(words, position))) {
        phrase.everything = true;  // "put all in the box"
      } else if (position < words.size() && !endsPhrase(words, position)) {
        phrase.unknownNoun = true;
        for (int extra = 0; extra < 3 && position < words.size() && !endsPhrase(words, position);
             ++extra) {
          ++position;
        }
      } else if (!adjectives && phrase.count == 0) {
        return std::nullopt;
      }
    }
  }
  position = readRankFrom(words, position, phrase);
  position = readModifier(words, position, phrase);
  const std::size_t negated = negatedClauseWords(words, position);  // "the object that is not the eraser"
  if (const std::size_t exception = negated > 0 ? negated : exceptionWords(words, position);
      exception > 0 && (negated > 0 || phrase.isPlural() || phrase.everything || phrase.quantity == Quantity::kAll)) {
    phrase.except = readList(words, position + exception);
    if (!phrase.except.empty()) position = phrase.except.back().end;
  }
  phrase.end = position;
  phrase.text = joinWords(words, phrase.begin, phrase.end);
  return phrase;
}



std::size_t NounPhraseReader::readRankFrom(const Words& words, std::size_t at, NounPhrase& phrase) {
  if (phrase.rank == 0) return at;
  static const std::vector<std::pair<Words, RankFrom>> sides{
      {{"from", "the", "left"}, RankFrom::kLeft},     {{"from", "the", "right"}, RankFrom::kRight},
      {{"from", "the", "top"}, RankFrom::kTop},       {{"from", "the", "bottom"}, RankFrom::kBottom},
      {{"from", "the", "far", "side"}, RankFrom::kTop}, {{"from", "the", "back"}, RankFrom::kBottom},
      {{"from", "the", "front"}, RankFrom::kTop},     {{"from", "left"}, RankFrom::kLeft},
      {{"from", "right"}, RankFrom::kRight},          {{"from", "top"}, RankFrom::kTop},
      {{"from", "bottom"}, RankFrom::kBottom},        {{"from", "the", "robot"}, RankFrom::kBottom},
      {{"counting", "from", "the", "left"}, RankFrom::kLeft}, {{"counting", "from", "the", "right"}, RankFrom::kRight}};
  for (const auto& [phraseWords, side] : sides) {
    if (!matchesAt(words, at, phraseWords)) continue;
    phrase.rankFrom = side;
    phrase.rankFromGiven = true;
    return at + phraseWords.size();
  }
  return at;
}

bool NounPhraseReader::headIsAmbiguous(const NounPhrase& phrase) const {
  if (phrase.isPlural() || phrase.size != SizeWord::kNone || phrase.place != PlaceWord::kNone || phrase.rank != 0) return false;
  if (phrase.one || phrase.other) return true;
  std::size_t count = 0;
  for (const ObjectDescriptor& object : objects_) {
    const bool named = !phrase.noun || containsWord(phrase.noun->objects, object.name);
    const bool coloured = std::all_of(phrase.colours.begin(), phrase.colours.end(),
                                      [&object](const std::string& colour) { return containsWord(object.colours, colour); });
    if (named && coloured) ++count;
  }
  return count > 1;
}


std::vector<NounPhrase> NounPhraseReader::readList(const Words& words, std::size_t at) const {
  std::vector<NounPhrase> list;
  std::optional<NounPhrase> phrase = read(words, at);
  while (phrase) {
    list.push_back(*phrase);
    std::size_t next = phrase->end;
    if (next < words.size() && words[next] == ",") ++next;
    if (matchesAt(words, next, {"as", "well", "as"})) next += 3;
    else if (next < words.size() && (words[next] == "and" || words[next] == "plus")) ++next;
    if (next == phrase->end) break;
    phrase = read(words, next);
  }
  for (std::size_t i = 0; i < list.size(); ++i) {
    NounPhrase& item = list[i];
    const bool elided = !item.noun && !item.one && !item.everything && !item.unknownNoun &&
                        item.pronoun == Pronoun::kNone;
    if (!elided) continue;
    for (std::size_t j = i + 1; j < list.size() && !item.noun; ++j) {
      if (list[j].noun) item.noun = list[j].noun;
    }
    for (std::size_t j = i; j-- > 0 && !item.noun;) {
      if (list[j].noun) item.noun = list[j].noun;
    }
    if (item.noun) item.noun->borrowed = true;
  }
  return list;
}

const ObjectDescriptor& NounPhraseReader::descriptor(const std::string& name) const {
  for (const ObjectDescriptor& object : objects_) {
    if (object.name == name) return object;
  }
  throw PlanningError("unknown object \"" + name + "\" (objects: " + objectList() + ")");
}

std::string NounPhraseReader::objectList() const {
  std::vector<std::string> names;
  for (const ObjectDescriptor& object : objects_) names.push_back(object.name);
  return joinNames(names);
}

std::string NounPhraseReader::describe(const std::vector<std::string>& names) const {
  std::vector<std::string> described;
  for (const std::string& name : names) {
    const ObjectDescriptor& object = descriptor(name);
    std::string text = name;
    if (!object.colours.empty()) text += " (" + joinNames(object.colours, "/") + ")";
    described.push_back(text);
  }
  return joinNames(described);
}

}  // namespace lang2manip::language_detail
