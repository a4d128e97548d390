#include "lang2manip/language/typo_correction.hpp"

#include <algorithm>
#include <cctype>
#include <map>

#include "lang2manip/language/noun_phrase.hpp"
#include "lang2manip/language/vocabulary.hpp"

namespace lang2manip::language_detail {
namespace {

constexpr std::size_t kShortestCorrected = 4;
constexpr std::size_t kLongWord = 8;

/// Words of instructions that no table of the vocabulary holds, so that they are never read as a
/// near object or verb ("more" is not "move", "left" is not "lift").
const std::set<std::string>& functionWords() {
  static const std::set<std::string> words{
      "then", "that", "this", "these", "those", "with", "from", "into", "onto", "each", "every", "both", "please", "could", "would",
      "should", "kindly", "there", "where", "which", "what", "when", "while", "after", "before", "until", "first", "second", "third",
      "fourth", "fifth", "last", "finally", "also", "again", "other", "another", "some", "same", "thing", "things", "object", "objects",
      "item", "items", "ones", "them", "their", "have", "want", "like", "need", "make", "sure", "just", "more", "less", "away", "back",
      "down", "over", "under", "next", "near", "close", "closer", "closest", "nearest", "farthest", "furthest", "left", "right", "front",
      "behind", "middle", "centre", "center", "corner", "corners", "side", "sides", "edge", "edges", "half", "quadrant", "line", "lines",
      "horizontal", "vertical", "diagonal", "column", "matching", "mismatched", "mismatching", "colour", "color", "colours",
      "colors", "different", "separate", "little", "slightly", "degrees", "degree", "quarter", "clockwise", "counterclockwise",
      "anticlockwise", "table", "desk", "robot", "home", "position", "place", "spot", "using", "planner", "grasp", "without", "except",
      "excluding", "than", "rather", "instead", "upper", "lower", "everything", "anything", "nothing", "something", "tower", "pyramid",
      "inside", "outside", "beside", "between", "toward", "towards", "along", "across", "around", "about", "roughly", "approximately",
      "they", "them", "your", "mine", "yours", "will", "shall", "must", "does", "done", "want", "wish", "bowl", "bowls", "block",
      "blocks", "cube", "cubes", "held", "hold", "holding", "gripper", "hand", "same", "once", "twice", "times", "turn", "turned",
      "point", "pointing", "facing", "face", "faces", "long", "short", "tall", "small", "large", "big", "bigger", "smaller", "largest",
      "smallest", "tallest", "shortest", "longest", "biggest", "round", "square", "flat", "only", "all", "none", "many", "much", "most",
      "least", "even", "evenly", "spaced", "apart", "together", "other", "others", "remaining", "rest", "movable", "moveable", "loose",
      "fixed", "thanks", "thank", "okay", "well", "good", "nice", "neat", "neatly", "careful", "carefully", "gently", "quickly", "slowly",
      "now", "right", "here", "there", "sort", "sorted", "colored", "coloured", "same", "wrong", "own", "four", "three", "five", "zero",
      "gray", "violet", "magenta", "navy", "crimson", "scarlet", "teal", "turquoise", "beige", "gold", "silver", "lime", "maroon",
      "olive", "dark", "light", "bright", "pale", "circle", "circles", "ring", "triangle", "triangles", "squares", "circular",
      "triangular", "shape", "shapes", "group", "grouped", "cluster", "clustered", "bunch", "formation", "pattern", "arrangement", "layout", "row", "rows", "spread", "scatter",
      "scattered", "space", "distribute", "distributed", "equally", "equal", "equidistant", "form", "forming", "create", "build",
      "surrounding", "horizontally", "vertically", "single", "straight", "perfect", "tidy", "regular", "equilateral"};
  return words;
}

bool knownWord(const std::string& word, const std::set<std::string>& known) {
  if (known.count(word) || functionWords().count(word)) return true;
  const std::vector<std::string> singulars = singularCandidates(word);
  return std::any_of(singulars.begin(), singulars.end(), [&](const std::string& s) { return known.count(s) || functionWords().count(s); });
}

bool correctable(const std::string& word) {
  return word.size() >= kShortestCorrected && std::all_of(word.begin(), word.end(), [](char c) { return std::isalpha(static_cast<unsigned char>(c)); });
}

/// What a typo may be of, with a rank that breaks ties between words as near: the words of the
/// objects' names, kinds and synonyms (0), the colours (1), region and arrangement words (2), verbs (3).
std::map<std::string, int> targetWords(const std::vector<ObjectDescriptor>& objects) {
  std::map<std::string, int> targets;
  const auto add = [&targets](const std::string& word, int rank) {
    if (!correctable(word)) return;
    const auto [at, inserted] = targets.emplace(word, rank);
    if (!inserted) at->second = std::min(at->second, rank);
  };
  for (const ObjectDescriptor& object : objects) {
    for (const std::string& text : {object.name, object.kind}) {
      for (const Words& words : {nameWords(text), tokenize(text)}) {
        for (const std::string& word : words) add(word, 0);
      }
    }
    for (const std::string& synonym : object.synonyms) {
      for (const std::string& word : tokenize(synonym)) add(word, 0);
    }
  }
  for (const std::string& colour : colourNames()) add(colour, 1);
  for (const char* word : {"corner", "corners", "middle", "centre", "center", "left", "right", "bottom", "matching", "mismatched",
                           "horizontal", "vertical", "diagonal", "colour", "color", "colours", "colors", "block", "blocks", "bowl",
                           "bowls", "different", "closest", "farthest", "table"}) {
    add(word, 2);
  }
  for (const std::string& verb : vocabulary::verbWords()) add(verb, 3);
  return targets;
}

}  // namespace

std::size_t editDistance(const std::string& a, const std::string& b, std::size_t limit) {
  const std::size_t n = a.size(), m = b.size();
  if ((n > m ? n - m : m - n) > limit) return limit + 1;
  std::vector<std::vector<std::size_t>> d(n + 1, std::vector<std::size_t>(m + 1));
  for (std::size_t i = 0; i <= n; ++i) d[i][0] = i;
  for (std::size_t j = 0; j <= m; ++j) d[0][j] = j;
  for (std::size_t i = 1; i <= n; ++i) {
    for (std::size_t j = 1; j <= m; ++j) {
      const std::size_t cost = a[i - 1] == b[j - 1] ? 0 : 1;
      d[i][j] = std::min({d[i - 1][j] + 1, d[i][j - 1] + 1, d[i - 1][j - 1] + cost});
      if (i > 1 && j > 1 && a[i - 1] == b[j - 2] && a[i - 2] == b[j - 1]) d[i][j] = std::min(d[i][j], d[i - 2][j - 2] + 1);
    }
  }
  return std::min(d[n][m], limit + 1);
}

std::vector<Correction> correctTypos(Words& words, const std::vector<ObjectDescriptor>& objects) {
  const std::set<std::string> known = vocabulary::knownWords();
  std::map<std::string, int> targets;
  std::vector<Correction> corrections;
  for (std::string& word : words) {
    if (!correctable(word) || knownWord(word, known)) continue;
    if (targets.empty()) targets = targetWords(objects);
    const std::vector<std::string> singulars = singularCandidates(word);
    const auto isTarget = [&](const std::string& w) { return targets.count(w) > 0; };
    if (isTarget(word) || std::any_of(singulars.begin(), singulars.end(), isTarget)) continue;
    const std::size_t limit = word.size() >= kLongWord ? 2 : 1;
    std::size_t best = limit + 1;
    int bestRank = 0;
    std::vector<std::string> nearest;
    for (const auto& [target, rank] : targets) {
      const std::size_t distance = editDistance(word, target, limit);
      if (distance > limit || distance > best || (distance == best && rank > bestRank)) continue;
      if (distance < best || rank < bestRank) nearest.clear(), best = distance, bestRank = rank;
      nearest.push_back(target);
    }
    if (nearest.empty()) continue;
    if (nearest.size() > 1) throwGroundingError(word, "it is a typo of " + joinAlternatives(nearest) + "? say which");
    corrections.push_back({word, nearest.front()});
    word = nearest.front();
  }
  return corrections;
}

std::string correctionsText(const std::vector<Correction>& corrections) {
  std::string text;
  for (const Correction& correction : corrections) {
    text += (text.empty() ? "" : "; ") + std::string("read \"") + correction.typed + "\" as \"" + correction.read + "\"";
  }
  return text;
}

}  // namespace lang2manip::language_detail
