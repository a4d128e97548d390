#include "lang2manip/language/instruction_corpus.hpp"

#include <algorithm>
#include <fstream>
#include <sstream>

#include "lang2manip/core/error.hpp"
#include "lang2manip/core/file_checks.hpp"

namespace lang2manip {
namespace {

std::vector<std::string_view> splitTabs(std::string_view line) {
  std::vector<std::string_view> fields;
  std::size_t start = 0;
  while (true) {
    const std::size_t tab = line.find('\t', start);
    fields.push_back(line.substr(start, tab == std::string_view::npos ? std::string_view::npos : tab - start));
    if (tab == std::string_view::npos) return fields;
    start = tab + 1;
  }
}

bool isClassName(std::string_view name) {
  return !name.empty() && std::all_of(name.begin(), name.end(), [](char c) {
    return (c >= 'a' && c <= 'z') || (c >= '0' && c <= '9') || c == '_';
  });
}

CorpusInstruction parseLine(std::string_view line, const std::string& where) {
  const std::vector<std::string_view> fields = splitTabs(line);
  if (fields.size() != 3) {
    throw InputError(where + ": expected 3 tab-separated fields (class, expect, instruction), got " + std::to_string(fields.size()));
  }
  CorpusInstruction entry;
  if (!isClassName(fields[0])) throw InputError(where + ": the class must be lower-case letters, digits and '_', got \"" + std::string(fields[0].substr(0, 40)) + "\"");
  entry.group = std::string(fields[0]);
  if (fields[1] == "execute") entry.expect = CorpusExpectation::kExecute;
  else if (fields[1] == "refuse") entry.expect = CorpusExpectation::kRefuse;
  else throw InputError(where + ": expect must be \"execute\" or \"refuse\", got \"" + std::string(fields[1].substr(0, 40)) + "\"");
  if (fields[2].find_first_not_of(" ") == std::string_view::npos) throw InputError(where + ": the instruction is empty");
  if (fields[2].size() > kMaxCorpusInstruction) {
    throw InputError(where + ": the instruction is " + std::to_string(fields[2].size()) + " bytes long (at most " +
                     std::to_string(kMaxCorpusInstruction) + ")");
  }
  entry.instruction = std::string(fields[2]);
  return entry;
}

}  // namespace

std::vector<CorpusInstruction> parseInstructionCorpus(std::string_view text, const std::string& source) {
  std::vector<CorpusInstruction> corpus;
  int number = 0;
  std::size_t start = 0;
  while (start < text.size()) {
    const std::size_t end = std::min(text.find('\n', start), text.size());
    std::string_view line = text.substr(start, end - start);
    start = end + 1;
    ++number;
    if (!line.empty() && line.back() == '\r') line.remove_suffix(1);
    if (line.empty() || line.front() == '#') continue;
    CorpusInstruction entry = parseLine(line, source + ":" + std::to_string(number));
    entry.line = number;
    corpus.push_back(std::move(entry));
  }
  if (corpus.empty()) throw InputError(source + ": no instructions (lines \"class<TAB>expect<TAB>instruction\")");
  return corpus;
}

std::vector<CorpusInstruction> readInstructionCorpus(const std::filesystem::path& file) {
  requireRegularFile(file, "instruction corpus");
  std::ifstream in(file, std::ios::binary);
  std::ostringstream text;
  text << in.rdbuf();
  if (!in && !in.eof()) throw InputError("instruction corpus " + file.string() + ": cannot be read");
  return parseInstructionCorpus(text.str(), file.string());
}

std::string corpusExpectationName(CorpusExpectation expect) {
  return expect == CorpusExpectation::kExecute ? "execute" : "refuse";
}

}  // namespace lang2manip
