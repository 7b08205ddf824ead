// is_plain_decimal reads by hand what it matched with a std::regex before: both must agree
// on every text, or an option or upload field would take or refuse a different number.
#include "host/lib/plan/plain_decimal.h"

#include <gtest/gtest.h>

#include <regex>   // std::regex: the rule as it was written
#include <string>  // std::string

namespace host {
namespace {

TEST(PlainDecimal, AgreesWithTheRegexOnEveryShortText) {
  const std::regex decimal(R"([+-]?([0-9]+\.?[0-9]*|\.[0-9]+)([eE][+-]?[0-9]+)?)");
  // Every text of up to 6 characters over the characters that matter, and a few that don't.
  const std::string alphabet = "07+-.eE x";
  std::string text;
  size_t checked = 0, accepted = 0;
  const auto check = [&](const auto& self, size_t length) -> void {
    const bool expected = std::regex_match(text, decimal);
    ASSERT_EQ(is_plain_decimal(text), expected) << "'" << text << "'";
    ++checked;
    accepted += expected ? 1 : 0;
    if (length == 6) return;
    for (char c : alphabet) {
      text.push_back(c);
      self(self, length + 1);
      text.pop_back();
      if (HasFatalFailure()) return;
    }
  };
  check(check, 0);
  EXPECT_EQ(checked, 597871u);  // 1 + 9 + 81 + ... + 9^6
  EXPECT_GT(accepted, 1000u);
}

TEST(PlainDecimal, TheDocumentedExamples) {
  for (const char* yes : {"10", "-1.5", "+10", "10.", ".5e1", "0.2", "1e-3", "2E+2"})
    EXPECT_TRUE(is_plain_decimal(yes)) << yes;
  for (const char* no :
       {"0x10", " 10", "nan", "inf", "1,5", "", ".", "+", "1e", "1e+", "e5", "1.5.", "10 ", "--1"})
    EXPECT_FALSE(is_plain_decimal(no)) << no;
  EXPECT_FALSE(is_plain_decimal(std::string("1\0", 2)));
  EXPECT_TRUE(is_whole_decimal("2.0"));
  EXPECT_FALSE(is_whole_decimal("1.5"));
}

}  // namespace
}  // namespace host
