#include "lang2manip/language/words.hpp"

#include <algorithm>
#include <array>
#include <cctype>
#include <utility>

namespace lang2manip {
namespace {

enum class CharClass { kLetter, kDigit, kSeparator, kPunctuation };

bool isAsciiLetter(char c) { return std::isalpha(static_cast<unsigned char>(c)) != 0; }
bool isAsciiDigit(char c) { return std::isdigit(static_cast<unsigned char>(c)) != 0; }

CharClass classify(char c) {
  if (isAsciiDigit(c)) return CharClass::kDigit;
  switch (c) {
    case ',': case ';': case '.': case '!': case '?': case ':':
      return CharClass::kPunctuation;
    case ' ': case '\t': case '\n': case '\r': case '_': case '-': case '/': case '"':
    case '(': case ')': case '[': case ']': case '{': case '}': case '`':
      return CharClass::kSeparator;
    default:
      return CharClass::kLetter;  // letters, '*', apostrophes, non-ASCII bytes
  }
}

class Tokenizer {
 public:
  explicit Tokenizer(std::string_view text) : text_(text) {}

  Words run() {
    for (std::size_t i = 0; i < text_.size(); ++i) step(i);
    flush();
    return std::move(words_);
  }

 private:
  void step(std::size_t i) {
    const char c = text_[i];
    const CharClass kind = classify(c);
    if (c == '.' && inNumber_ && i + 1 < text_.size() && isAsciiDigit(text_[i + 1])) {
      current_ += c;
      return;
    }
    if (c == '\'' && !(i + 1 < text_.size() && isAsciiLetter(text_[i + 1]) && !current_.empty())) {
      flush();
      return;
    }
    switch (kind) {
      case CharClass::kSeparator:
        flush();
        return;
      case CharClass::kPunctuation:
        flush();
        words_.emplace_back(1, c);
        return;
      case CharClass::kDigit:
        if (!current_.empty() && !inNumber_) flush();
        inNumber_ = true;
        current_ += c;
        return;
      case CharClass::kLetter:
        if (inNumber_) flush();
        current_ += static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
        return;
    }
  }

  void flush() {
    if (!current_.empty()) words_.push_back(std::move(current_));
    current_.clear();
    inNumber_ = false;
  }

  std::string_view text_;
  Words words_;
  std::string current_;
  bool inNumber_ = false;
};

constexpr std::array<std::pair<const char*, int>, 20> kNumberWords{{
    {"one", 1},       {"two", 2},        {"three", 3},     {"four", 4},     {"five", 5},
    {"six", 6},       {"seven", 7},      {"eight", 8},     {"nine", 9},     {"ten", 10},
    {"eleven", 11},   {"twelve", 12},    {"thirteen", 13}, {"fourteen", 14}, {"fifteen", 15},
    {"sixteen", 16},  {"seventeen", 17}, {"eighteen", 18}, {"nineteen", 19}, {"twenty", 20},
}};

bool endsWith(const std::string& word, std::string_view suffix) {
  return word.size() > suffix.size() &&
         word.compare(word.size() - suffix.size(), suffix.size(), suffix) == 0;
}

}  // namespace

Words tokenize(std::string_view text) { return Tokenizer(text).run(); }

Words nameWords(std::string_view name) {
  std::string spaced;
  for (std::size_t i = 0; i < name.size(); ++i) {
    const bool lowerToUpper = i > 0 && std::islower(static_cast<unsigned char>(name[i - 1])) && std::isupper(static_cast<unsigned char>(name[i]));
    if (lowerToUpper) spaced += ' ';
    spaced += name[i];
  }
  return tokenize(spaced);
}

std::string headNoun(const Words& words) {
  for (auto word = words.rbegin(); word != words.rend(); ++word) {
    if (word->size() >= 2 && !std::isdigit(static_cast<unsigned char>(word->front()))) return *word;
  }
  return {};
}

std::string joinWords(const Words& words, std::size_t begin, std::size_t end) {
  std::string text;
  for (std::size_t i = begin; i < end && i < words.size(); ++i) {
    if (!text.empty() && !isPunctuation(words[i])) text += ' ';
    text += words[i];
  }
  return text;
}

std::string joinWords(const Words& words) { return joinWords(words, 0, words.size()); }

bool matchesAt(const Words& words, std::size_t at, const Words& phrase) {
  if (phrase.empty() || at + phrase.size() > words.size()) return false;
  for (std::size_t i = 0; i < phrase.size(); ++i) {
    if (words[at + i] != phrase[i]) return false;
  }
  return true;
}

std::size_t longestPhraseAt(const Words& words, std::size_t at, const std::vector<Words>& phrases) {
  std::size_t best = 0;
  for (const Words& phrase : phrases) {
    if (phrase.size() > best && matchesAt(words, at, phrase)) best = phrase.size();
  }
  return best;
}

std::optional<double> numberValue(const std::string& word) {
  if (!word.empty() && isAsciiDigit(word.front())) {
    std::size_t dots = 0;
    for (char c : word) {
      if (c == '.') ++dots;
      else if (!isAsciiDigit(c)) return std::nullopt;
    }
    if (dots > 1 || word.back() == '.') return std::nullopt;
    return std::stod(word);
  }
  for (const auto& [name, value] : kNumberWords) {
    if (word == name) return static_cast<double>(value);
  }
  return std::nullopt;
}

bool isPunctuation(const std::string& word) {
  return word.size() == 1 && classify(word.front()) == CharClass::kPunctuation;
}

std::vector<std::string> singularCandidates(const std::string& word) {
  std::vector<std::string> result;
  if (endsWith(word, "ies")) result.push_back(word.substr(0, word.size() - 3) + "y");
  if (endsWith(word, "es")) result.push_back(word.substr(0, word.size() - 2));
  if (endsWith(word, "s") && !endsWith(word, "ss")) result.push_back(word.substr(0, word.size() - 1));
  return result;
}

bool containsWord(const Words& list, const std::string& word) {
  return std::find(list.begin(), list.end(), word) != list.end();
}

std::string joinNames(const std::vector<std::string>& names, const char* separator) {
  std::string text;
  for (const std::string& name : names) {
    if (!text.empty()) text += separator;
    text += name;
  }
  return text;
}

std::string joinAlternatives(const std::vector<std::string>& names) {
  std::string text;
  for (std::size_t i = 0; i < names.size(); ++i) {
    if (i > 0) text += i + 1 == names.size() ? " or " : ", ";
    text += names[i];
  }
  return text;
}

}  // namespace lang2manip
