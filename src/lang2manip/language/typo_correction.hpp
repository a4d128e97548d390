#pragma once
/// @file Typos in instructions (internal to the language module): a word that is no word the
/// planner knows, but one edit (two for words of eight letters or more; swapped neighbours count
/// as one) from exactly one word of the scene's object names and nouns, the colours, the verbs or
/// the region words, is read as that word; the corrections are stated in the plan's reasoning. A
/// word as close to two such words is refused, naming both.

#include <set>
#include <string>
#include <vector>

#include "lang2manip/language/object_descriptor.hpp"
#include "lang2manip/language/words.hpp"

namespace lang2manip::language_detail {

struct Correction {
  std::string typed;
  std::string read;
};

/// The optimal-string-alignment distance between `a` and `b` (insertions, deletions, substitutions
/// and swaps of neighbours), or `limit` + 1 when it exceeds `limit`.
std::size_t editDistance(const std::string& a, const std::string& b, std::size_t limit);

/// Replaces the typos of `words` (see the file comment) and returns what it read them as. Throws
/// PlanningError for a word that is as close to two different words.
std::vector<Correction> correctTypos(Words& words, const std::vector<ObjectDescriptor>& objects);

/// "read \"markr\" as \"marker\"; ..." (empty when there are none).
std::string correctionsText(const std::vector<Correction>& corrections);

}  // namespace lang2manip::language_detail
