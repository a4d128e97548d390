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
  /// "one block in each bowl": the objects are every candidate of a singular indefinite phrase,
  /// and each place that follows gets one of them (parseAssignment).
  bool distributive = false;
  bool putsDown = false;
  /// No verb: the step repeats the previous verb (and its place, when it names none).
  bool elliptical = false;
  std::string target;
  std::size_t firstGoal = 0;

  [[nodiscard]] bool atEnd() const { return at >= words.size(); }
  [[nodiscard]] bool next(const char* word) const { return !atEnd() && words[at] == word; }
};

/// Whether words[at] starts a place given to each object in turn: "in each bowl", "into every
/// cup", "per corner", "in each of the corners" (assignment_steps.cpp).
bool eachPlaceFollows(const Words& words, std::size_t at);

}  // namespace lang2manip::language_detail
