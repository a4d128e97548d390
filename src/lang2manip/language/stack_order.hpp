#pragma once
/// @file A tower in a given order said as one list before an instruction is split into steps
/// (internal to the language module): "stack the blocks in this order from the bottom: blue,
/// grey, pink", "build a tower with the brown block at the bottom, then the blue block, then the
/// red block on top" read as "stack the blue block, the grey block and the pink block" (the
/// first named at the bottom).

#include <optional>

#include "lang2manip/language/noun_phrase.hpp"
#include "lang2manip/language/words.hpp"

namespace lang2manip::language_detail {

/// `words` rewritten as one stacking step listing the objects bottom first, when they state a
/// tower's order ("in this order", "from the top", "at the bottom", "on top", "then"); none
/// otherwise, and when an item of the list does not read as an object.
std::optional<Words> orderedStack(const Words& words, const NounPhraseReader& reader);

}  // namespace lang2manip::language_detail
