// core/csv: RFC 4180 fields written and read back (issue 44: a map name with a comma broke
// runs.csv).
#include "core/csv.hpp"

#include <gtest/gtest.h>

#include "core/error.hpp"

namespace plumekit {
namespace {

using Records = std::vector<std::vector<std::string>>;

TEST(Csv, QuotesAFieldOnlyWhenItMust) {
  EXPECT_EQ(csv_field("test-1-block"), "test-1-block");
  EXPECT_EQ(csv_field(""), "");
  EXPECT_EQ(csv_field("hall, east"), "\"hall, east\"");
  EXPECT_EQ(csv_field("the \"big\" hall"), "\"the \"\"big\"\" hall\"");
  EXPECT_EQ(csv_field("two\nlines"), "\"two\nlines\"");
  EXPECT_EQ(csv_field("cr\r"), "\"cr\r\"");
}

TEST(Csv, ReadsBackWhatItWrites) {
  const std::vector<std::string> names = {
      "plain", "hall, east", "the \"big\" hall", "two\nlines", "", "\"", ","};
  std::string text = "name,n\n";
  for (std::size_t k = 0; k < names.size(); ++k)
    text += csv_field(names[k]) + "," + std::to_string(k) + "\n";
  const Records r = parse_csv(text, "runs.csv");
  ASSERT_EQ(r.size(), names.size() + 1);
  EXPECT_EQ(r[0], (std::vector<std::string>{"name", "n"}));
  for (std::size_t k = 0; k < names.size(); ++k)
    EXPECT_EQ(r[k + 1], (std::vector<std::string>{names[k], std::to_string(k)})) << k;
}

TEST(Csv, LineEndsAndEmptyFields) {
  EXPECT_EQ(parse_csv("a,b\r\n1,\r\n", "f"), (Records{{"a", "b"}, {"1", ""}}));
  EXPECT_EQ(parse_csv("a,b\n1,2", "f"), (Records{{"a", "b"}, {"1", "2"}}));  // no last break
  EXPECT_EQ(parse_csv("a,", "f"), (Records{{"a", ""}}));
  EXPECT_TRUE(parse_csv("", "f").empty());
}

TEST(Csv, RefusesAnOpenQuoteOrTextAfterAClosingOneNamingTheLine) {
  try {
    parse_csv("a,b\n\"open,1\n2,3\n", "runs.csv");
    FAIL() << "an open quote was accepted";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("runs.csv:2: a quoted field is not closed"),
              std::string::npos)
        << e.what();
  }
  try {
    parse_csv("a,b\n1,2\n\"x\"y,3\n", "runs.csv");
    FAIL() << "text after a closing quote was accepted";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("runs.csv:3: text after"), std::string::npos) << e.what();
  }
}

}  // namespace
}  // namespace plumekit
