// The corpus of instructions `bench instructions` measures (data/corpus/instructions.tsv): its
// format and its errors, and that the built-in corpus covers every class of issue 15 with at
// least 15 phrasings.

#include <fstream>
#include <map>
#include <set>

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "lang2manip/core/error.hpp"
#include "lang2manip/language/instruction_corpus.hpp"
#include "lang2manip/model/builtin_data.hpp"

namespace lang2manip {
namespace {

using ::testing::HasSubstr;

TEST(InstructionCorpusFile, LinesAreClassExpectationAndInstruction) {
  const std::vector<CorpusInstruction> corpus =
      parseInstructionCorpus("# comment\n\ncontainer\texecute\tput the marker in the holder\r\nrotate\trefuse\tturn the holder\n", "c.tsv");
  ASSERT_EQ(corpus.size(), 2u);
  EXPECT_EQ(corpus[0].group, "container");
  EXPECT_EQ(corpus[0].expect, CorpusExpectation::kExecute);
  EXPECT_EQ(corpus[0].instruction, "put the marker in the holder");
  EXPECT_EQ(corpus[0].line, 3);
  EXPECT_EQ(corpus[1].expect, CorpusExpectation::kRefuse);
  EXPECT_EQ(corpusExpectationName(corpus[1].expect), "refuse");
}

TEST(InstructionCorpusFile, EveryMalformedLineIsNamedByFileAndLine) {
  const std::pair<std::string, std::string> cases[] = {
      {"container\texecute", "c.tsv:1: expected 3 tab-separated fields (class, expect, instruction), got 2"},
      {"a\tb\tc\td", "got 4"},
      {"Container\texecute\tput it", "c.tsv:1: the class must be lower-case letters, digits and '_'"},
      {"\texecute\tput it", "the class must be"},
      {"# x\ncontainer\tmaybe\tput it", "c.tsv:2: expect must be \"execute\" or \"refuse\", got \"maybe\""},
      {"container\texecute\t   ", "c.tsv:1: the instruction is empty"},
      {"container\texecute\t" + std::string(1001, 'a'), "is 1001 bytes long (at most 1000)"},
      {"# only comments\n", "c.tsv: no instructions"},
      {"", "c.tsv: no instructions"},
  };
  for (const auto& [text, message] : cases) {
    SCOPED_TRACE(text.substr(0, 60));
    try {
      (void)parseInstructionCorpus(text, "c.tsv");
      ADD_FAILURE() << "accepted";
    } catch (const InputError& error) {
      EXPECT_THAT(error.what(), HasSubstr(message));
    }
  }
  EXPECT_THROW((void)readInstructionCorpus("/nonexistent/corpus.tsv"), InputError);
}

TEST(InstructionCorpusFile, TheBuiltInCorpusCoversEveryClassWithFifteenPhrasingsOrMore) {
  const std::vector<CorpusInstruction> corpus = readInstructionCorpus(builtinDataDirectory() / "corpus" / "instructions.tsv");
  EXPECT_GE(corpus.size(), 300u);
  std::map<std::string, int> perClass;
  std::set<std::string> distinct;
  for (const CorpusInstruction& entry : corpus) {
    ++perClass[entry.group];
    distinct.insert(entry.instruction);
  }
  EXPECT_EQ(distinct.size(), corpus.size()) << "an instruction is listed twice";
  for (const char* group : {"intermediate", "container", "reference", "stacking", "rearrange", "rotate", "carry_handover", "any_pose", "regions"}) {
    EXPECT_GE(perClass[group], 15) << group;
  }
  EXPECT_EQ(perClass.size(), 9u);
}

}  // namespace
}  // namespace lang2manip
