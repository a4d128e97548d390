#pragma once
/// @file Words of an instruction: a tokenizer that lower-cases text and splits it into words,
/// numbers and punctuation, and helpers to match fixed phrases against a word sequence.
/// Used by the instruction parser and to turn object names ("pen_holder") into words.

#include <cstddef>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

namespace lang2manip {

using Words = std::vector<std::string>;

/// Lower-cased words of `text`. Splits at spaces, '_', '-', '/', quotes and brackets, and
/// between letters and digits ("5cm" -> "5", "cm"; "cup1" -> "cup", "1"); keeps ',', ';', '.',
/// '!', '?' and ':' as words of their own (a '.' between digits stays in the number); keeps '*'
/// and apostrophes inside words ("rrt*", "don't").
Words tokenize(std::string_view text);

/// The words of an object's name or kind as a person reads them: tokenize() after splitting
/// where a lower-case letter meets a capital ("queenW" -> "queen", "w"; "pawnB1" -> "pawn", "b",
/// "1"; "woodPiece" -> "wood", "piece"; "UR5" stays "ur", "5").
Words nameWords(std::string_view name);

/// The noun a name's words end on: the last word of two letters or more that is not a number
/// ("queen" of "queen w", "pawn" of "pawn b 1"); empty when there is none.
std::string headNoun(const Words& words);

/// The words [begin, end) joined by single spaces.
std::string joinWords(const Words& words, std::size_t begin, std::size_t end);
/// All of `words` joined by single spaces.
std::string joinWords(const Words& words);

/// True when `list` holds `word`.
bool containsWord(const Words& list, const std::string& word);

/// `names` joined by `separator` ("a, b, c").
std::string joinNames(const std::vector<std::string>& names, const char* separator = ", ");

/// `names` as alternatives: "a", "a or b", "a, b or c".
std::string joinAlternatives(const std::vector<std::string>& names);

/// True when `phrase` occurs in `words` starting at `at`.
bool matchesAt(const Words& words, std::size_t at, const Words& phrase);

/// The length of the longest of `phrases` that occurs in `words` at `at`; 0 when none does.
std::size_t longestPhraseAt(const Words& words, std::size_t at, const std::vector<Words>& phrases);

/// The value of a number word: digits with an optional decimal point ("2.5"), or an English
/// number word from "one" to "twenty" ("a" is not a number); nullopt otherwise.
std::optional<double> numberValue(const std::string& word);

/// True for ",", ";", ".", "!", "?", ":".
bool isPunctuation(const std::string& word);

/// The singular forms `word` may be the plural of ("boxes" -> "boxe", "box"; "blocks" ->
/// "block"; "batteries" -> "battery"); empty when it does not look like a plural.
std::vector<std::string> singularCandidates(const std::string& word);

}  // namespace lang2manip
