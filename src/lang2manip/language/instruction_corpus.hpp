#pragma once
/// @file A corpus of instructions for measuring task planners: each line a class, what should
/// happen (executed and verified, or refused) and the instruction, tab-separated
/// (data/corpus/instructions.tsv; `lang2manip bench instructions` runs it).

#include <filesystem>
#include <string>
#include <string_view>
#include <vector>

namespace lang2manip {

/// What should happen to an instruction: executed and verified, or refused with nothing moved.
enum class CorpusExpectation { kExecute, kRefuse };

struct CorpusInstruction {
  /// The class it measures ("container", "rotate", ...): lower-case letters, digits and '_'.
  std::string group;
  CorpusExpectation expect = CorpusExpectation::kExecute;
  std::string instruction;
  /// 1-based line in its source.
  int line = 0;
};

/// The longest instruction a corpus line may hold, in bytes.
inline constexpr std::size_t kMaxCorpusInstruction = 1000;

/// Parses corpus text: lines "class<TAB>expect<TAB>instruction" with expect "execute" or "refuse";
/// empty lines and lines starting with '#' are skipped; a trailing '\r' is dropped. Throws
/// InputError "<source>:<line>: what" for a line without exactly three fields, an empty or
/// malformed class, an unknown expectation, an empty or too long instruction, and for a corpus
/// without instructions.
std::vector<CorpusInstruction> parseInstructionCorpus(std::string_view text, const std::string& source);

/// Reads and parses `file` (InputError naming the file when it cannot be read).
std::vector<CorpusInstruction> readInstructionCorpus(const std::filesystem::path& file);

/// "execute", "refuse".
std::string corpusExpectationName(CorpusExpectation expect);

}  // namespace lang2manip
