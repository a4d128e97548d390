#include <gtest/gtest.h>

#include "lang2manip/language/words.hpp"

namespace lang2manip {
namespace {

TEST(WordsTest, TokenizeSplitsWordsNumbersAndPunctuation) {
  EXPECT_EQ(tokenize("Put the pen_holder 5cm LEFT, then go!"),
            (Words{"put", "the", "pen", "holder", "5", "cm", "left", ",", "then", "go", "!"}));
  EXPECT_EQ(tokenize("move it 2.5 cm. Done"), (Words{"move", "it", "2.5", "cm", ".", "done"}));
  EXPECT_EQ(tokenize("using RRT* (fast)"), (Words{"using", "rrt*", "fast"}));
  EXPECT_EQ(tokenize("I'd like cup1 top-down"), (Words{"i'd", "like", "cup", "1", "top", "down"}));
  EXPECT_EQ(tokenize("'quoted'"), (Words{"quoted"}));
  EXPECT_TRUE(tokenize("  \t\n").empty());
}

TEST(WordsTest, NumbersAndPlurals) {
  EXPECT_EQ(numberValue("5"), 5.0);
  EXPECT_EQ(numberValue("2.5"), 2.5);
  EXPECT_EQ(numberValue("three"), 3.0);
  EXPECT_FALSE(numberValue("a"));
  EXPECT_FALSE(numberValue("1.2.3"));
  EXPECT_FALSE(numberValue("5cm"));
  EXPECT_EQ(singularCandidates("boxes"), (std::vector<std::string>{"box", "boxe"}));
  EXPECT_EQ(singularCandidates("batteries"),
            (std::vector<std::string>{"battery", "batteri", "batterie"}));
  EXPECT_TRUE(singularCandidates("glass").empty());
  EXPECT_EQ(joinWords(Words{"put", "it", ",", "then"}), "put it, then");
  EXPECT_TRUE(matchesAt(Words{"a", "b", "c"}, 1, Words{"b", "c"}));
  EXPECT_FALSE(matchesAt(Words{"a", "b"}, 1, Words{"b", "c"}));
}

}  // namespace
}  // namespace lang2manip
