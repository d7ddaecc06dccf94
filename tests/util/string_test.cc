#include "util/string.h"

#include <gtest/gtest.h>

#include "util/error.h"

namespace colmap_gcn {
namespace {

TEST(StringSplit, KeepsEmptyFields) {
  EXPECT_EQ(StringSplit("a b", " "), (std::vector<std::string>{"a", "b"}));
  EXPECT_EQ(StringSplit("a  b", " "), (std::vector<std::string>{"a", "", "b"}));
  EXPECT_EQ(StringSplit("", " "), (std::vector<std::string>{""}));
}

TEST(StringTrim, RemovesSurroundingWhitespace) {
  EXPECT_EQ(StringTrim("  a b \t\r\n"), "a b");
  EXPECT_EQ(StringTrim(" \t "), "");
}

TEST(SplitCommaList, TrimsAndDropsEmptyItems) {
  EXPECT_EQ(SplitCommaList(" a.db, b c.db ,,"),
            (std::vector<std::string>{"a.db", "b c.db"}));
  EXPECT_TRUE(SplitCommaList(" , ").empty());
  EXPECT_TRUE(SplitCommaList("").empty());
}

TEST(ParseIntList, ParsesOrNamesTheOption) {
  EXPECT_EQ(ParseIntList("512, 256,", "--dims"), (std::vector<int>{512, 256}));
  EXPECT_TRUE(ParseIntList("", "--dims").empty());
  EXPECT_THROW(ParseIntList("512,25x", "--dims"), Error);
  EXPECT_THROW(ParseIntList("a", "--dims"), Error);
}

TEST(ShellQuote, QuotesOnlyWhenNeeded) {
  EXPECT_EQ(ShellQuote("--database_path=/a/b.db"), "--database_path=/a/b.db");
  EXPECT_EQ(ShellQuote("my file"), "'my file'");
  EXPECT_EQ(ShellQuote("it's"), "'it'\\''s'");
  EXPECT_EQ(ShellQuote(""), "''");
}

}  // namespace
}  // namespace colmap_gcn
