// Unit tests of the dictionary reader: grammar, validated lookups and the error messages users see.
#include <gtest/gtest.h>

#include "Dictionary.h"

using mixflow::Dictionary;
using mixflow::InputError;
using mixflow::Range;

namespace {
std::string errorOf(const std::function<void()>& f) {
  try {
    f();
  } catch (const InputError& e) {
    return e.what();
  }
  return "";
}
}  // namespace

TEST(Dictionary, ParsesEntriesSubDictionariesListsAndComments) {
  const Dictionary d = Dictionary::parse(
      "FoamFile { version 2.0; }\n// comment\na 1.5; /* block\n comment */ b word;\n"
      "c (1 2 3);\nsub { x 2; inner { y -3e-2; } }\n",
      "test.dict");
  EXPECT_DOUBLE_EQ(d.scalar("a", Range::positive()), 1.5);
  EXPECT_EQ(d.word("b", {}), "word");
  EXPECT_EQ(d.scalars("c", Range::any()), (std::vector<double>{1, 2, 3}));
  EXPECT_DOUBLE_EQ(d.subDict("sub").subDict("inner").scalar("y", Range::any()), -0.03);
  EXPECT_FALSE(d.has("FoamFile"));
  EXPECT_EQ(d.keys(), (std::vector<std::string>{"a", "b", "c", "sub"}));
}

TEST(Dictionary, RangeErrorNamesFileEntryLineAndRange) {
  const Dictionary d = Dictionary::parse("s\n{\n  n -2;\n}\n", "case/system/x");
  const std::string msg = errorOf([&] { d.subDict("s").scalar("n", Range::openClosed(0, 1)); });
  EXPECT_NE(msg.find("case/system/x"), std::string::npos) << msg;
  EXPECT_NE(msg.find("'s.n'"), std::string::npos) << msg;
  EXPECT_NE(msg.find("line 3"), std::string::npos) << msg;
  EXPECT_NE(msg.find("(0, 1]"), std::string::npos) << msg;
}

TEST(Dictionary, UnknownEntryListsAllowedOnes) {
  const Dictionary d = Dictionary::parse("alpha 1; betta 2;", "f");
  const std::string msg = errorOf([&] { d.allowOnly({"alpha", "beta"}); });
  EXPECT_NE(msg.find("'betta'"), std::string::npos) << msg;
  EXPECT_NE(msg.find("alpha, beta"), std::string::npos) << msg;
}

TEST(Dictionary, DefaultsOnlyWhenAbsent) {
  const Dictionary d = Dictionary::parse("a 3;", "f");
  EXPECT_DOUBLE_EQ(d.scalarOr("a", 7, Range::any()), 3);
  EXPECT_DOUBLE_EQ(d.scalarOr("b", 7, Range::any()), 7);
  EXPECT_DOUBLE_EQ(d.subDictOrEmpty("none").scalarOr("z", 4, Range::any()), 4);
  EXPECT_TRUE(d.switchOr("flag", true));
}

TEST(Dictionary, RejectsMalformedInput) {
  EXPECT_THROW(Dictionary::parse("a 1", "f"), InputError);        // no ';'
  EXPECT_THROW(Dictionary::parse("s { a 1; ", "f"), InputError);  // no '}'
  EXPECT_THROW(Dictionary::parse("a 1; a 2;", "f"), InputError);  // duplicate
  EXPECT_THROW(Dictionary::parse("a 1; }", "f"), InputError);     // stray '}'
  const Dictionary d = Dictionary::parse("n 1.5; w x; inf 1e400;", "f");
  EXPECT_THROW(d.integer("n", 0, 10), InputError);          // not whole
  EXPECT_THROW(d.word("w", {"y", "z"}), InputError);        // not allowed
  EXPECT_THROW(d.scalar("inf", Range::any()), InputError);  // overflow is not a number
  EXPECT_THROW(Dictionary::readFile("/nonexistent/dict"), InputError);
}

TEST(Dictionary, AutoOrNumberEntries) {
  const Dictionary d =
      Dictionary::parse("a auto; b 0.25; c many; n 3; m 2.5; k 40; s { x 1; }\n", "numerics.dict");
  EXPECT_FALSE(d.scalarOrAuto("a", Range::positive()).has_value());
  EXPECT_FALSE(d.scalarOrAuto("absent", Range::positive()).has_value());
  EXPECT_DOUBLE_EQ(*d.scalarOrAuto("b", Range::positive()), 0.25);
  EXPECT_EQ(*d.integerOrAuto("n", 1, 20), 3);
  // Each refusal names the file and the entry, and offers both choices.
  const std::string word = errorOf([&] { d.scalarOrAuto("c", Range::positive()); });
  EXPECT_NE(word.find("numerics.dict"), std::string::npos) << word;
  EXPECT_NE(word.find("'many' is not allowed: auto or a number in (0, inf)"), std::string::npos)
      << word;
  EXPECT_NE(errorOf([&] { d.integerOrAuto("m", 1, 20); }).find("whole number in [1, 20]"),
            std::string::npos);
  EXPECT_NE(errorOf([&] { d.integerOrAuto("k", 1, 20); }).find("outside the allowed range"),
            std::string::npos);
  EXPECT_NE(errorOf([&] { d.scalarOrAuto("s", Range::any()); }).find("auto or a number"),
            std::string::npos);
}

TEST(Dictionary, WordRefusalsSayWhatIsExpected) {
  const Dictionary d = Dictionary::parse("free a b; pick a b;", "names.dict");
  const std::string free = errorOf([&] { d.word("free", {}); });
  EXPECT_NE(free.find("must be one word; found 'a b'"), std::string::npos) << free;
  const std::string pick = errorOf([&] { d.word("pick", {"a", "c"}); });
  EXPECT_NE(pick.find("must be one word of: a, c; found 'a b'"), std::string::npos) << pick;
}

TEST(Range, OpenAndClosedEnds) {
  EXPECT_FALSE(Range::positive().contains(0.0));
  EXPECT_TRUE(Range::nonNegative().contains(0.0));
  EXPECT_TRUE(Range::openClosed(0, 1).contains(1.0));
  EXPECT_FALSE(Range::openClosed(0, 1).contains(0.0));
  EXPECT_FALSE(Range::any().contains(std::numeric_limits<double>::quiet_NaN()));
  EXPECT_EQ(Range::closed(1, 2).str(), "[1, 2]");
}
