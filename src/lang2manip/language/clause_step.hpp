#pragma once
/// @file Internal to the language module: the step StepParser reads, shared by its source files.

#include <string>
#include <vector>

#include "lang2manip/language/clause_parser.hpp"

namespace lang2manip::language_detail {

struct StepParser::Step {
  explicit Step(const Words& stepWords) : words(stepWords) {}

  const Words& words;
  std::size_t at = 0;
  vocabulary::Verb verb;
  std::vector<std::string> objects;
  /// Objects that came from plural phrases ("all the cups"): a target among them is left out.
  std::vector<std::string> groupObjects;
  bool listedExplicitly = true;
  bool putsDown = false;
  /// No verb: the step repeats the previous verb (and its place, when it names none).
  bool elliptical = false;
  std::string target;
  std::size_t firstGoal = 0;

  [[nodiscard]] bool atEnd() const { return at >= words.size(); }
  [[nodiscard]] bool next(const char* word) const { return !atEnd() && words[at] == word; }
};

}  // namespace lang2manip::language_detail
