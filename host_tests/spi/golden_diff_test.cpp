// Golden files (wildcards, repeats, errors) and the datagram alignment (= ~ - + marks).
#include <gtest/gtest.h>

#include "host/spi/diff.h"
#include "host/spi/golden.h"

using namespace host::spi;

namespace {

Frame word(uint32_t mosi, uint32_t miso = 0, bool has_miso = false) {
  Frame f;
  f.bit_count = 32;
  f.mosi = mosi;
  f.miso = miso;
  f.has_miso = has_miso;
  return f;
}

std::vector<Expected> golden(const std::string& text) {
  std::vector<Expected> out;
  Error e = parse_golden(text, &out);
  EXPECT_TRUE(e.ok()) << e.message;
  return out;
}

std::string marks(const DiffResult& d) {
  std::string s;
  for (const DiffStep& st : d.steps) s += static_cast<char>(st.mark);
  return s;
}

TEST(Golden, NibbleWildcardsXAndQuestionMarkMatchAnything) {
  Pattern p;
  ASSERT_TRUE(parse_pattern("0x03xxxx?9", &p));
  EXPECT_EQ(p.bits, 32);
  EXPECT_TRUE(pattern_matches(p, 0x03ABCDE9, 32));
  EXPECT_FALSE(pattern_matches(p, 0x04ABCDE9, 32));
  EXPECT_FALSE(pattern_matches(p, 0x03ABCDE8, 32));
  EXPECT_FALSE(pattern_matches(p, 0x03ABCDE9, 31));
  EXPECT_EQ(pattern_text(p), "0x03xxxxx9");
}

TEST(Golden, LinesCarryMisoRepeatAndComment) {
  auto g = golden(
      "# header\n\n0x7E010702  -   # SMGP\n0x03000000 0xxxFFFF38 {2,5}  # x_actual\n"
      "0x61000000 {1,}\n");
  ASSERT_EQ(g.size(), 3u);
  EXPECT_TRUE(g[0].miso.any);
  EXPECT_EQ(g[0].comment, "SMGP");
  EXPECT_EQ(g[0].line, 3);
  EXPECT_EQ(g[1].miso.mask, 0x00FFFFFFu);
  EXPECT_EQ(g[1].min_count, 2);
  EXPECT_EQ(g[1].max_count, 5);
  EXPECT_EQ(g[2].max_count, -1);
}

TEST(Golden, MalformedLineIsEGoldenWithItsNumber) {
  std::vector<Expected> out;
  Error e = parse_golden("0x12345678\n0x12G45678\n", &out);
  EXPECT_EQ(e.code, "E_GOLDEN");
  EXPECT_NE(e.message.find("line 2"), std::string::npos);
  EXPECT_EQ(parse_golden("0x12 0x1234\n", &out).code, "E_GOLDEN");  // widths differ
  EXPECT_EQ(parse_golden("0x12345678 {3,1}\n", &out).code, "E_GOLDEN");
  EXPECT_EQ(parse_golden("0x1 0x1 0x1\n", &out).code, "E_GOLDEN");
}

TEST(Golden, FormatThenParseGivesTheSameLines) {
  auto g = golden("0x03xxxxxx 0xxx000000 {1,} # a\n0x7E010702\n");
  auto again = golden(format_golden(g, "# h\n"));
  ASSERT_EQ(again.size(), 2u);
  EXPECT_EQ(pattern_text(again[0].mosi), "0x03xxxxxx");
  EXPECT_EQ(pattern_text(again[0].miso), "0xxx000000");
  EXPECT_EQ(again[0].max_count, -1);
  EXPECT_EQ(again[0].comment, "a");
}

TEST(Diff, IdenticalSequencesAreAllEqual) {
  auto g = golden("0x80000510\n0x7E010702\n0x08000064\n");
  DiffResult d;
  ASSERT_TRUE(diff_datagrams({word(0x80000510), word(0x7E010702), word(0x08000064)}, g, &d).ok());
  EXPECT_EQ(marks(d), "===");
  EXPECT_TRUE(d.same());
}

TEST(Diff, SameAddressDifferentDataIsASubstitution) {
  auto g = golden("0x80000510\n0x08000064\n0x7E010702\n");
  DiffResult d;
  ASSERT_TRUE(diff_datagrams({word(0x80000510), word(0x08000065), word(0x7E010702)}, g, &d).ok());
  EXPECT_EQ(marks(d), "=~=");
  EXPECT_EQ(d.changed, 1);
}

TEST(Diff, MissingAndExtraDatagramsAreMinusAndPlus) {
  auto g = golden("0x80000510\n0x82000304\n0x7E010702\n");
  DiffResult d;
  ASSERT_TRUE(diff_datagrams({word(0x80000510), word(0x7E010702), word(0x12000000)}, g, &d).ok());
  EXPECT_EQ(marks(d), "=-=+");
  EXPECT_EQ(d.steps[1].expected, 1);
  EXPECT_EQ(d.steps[3].frame, 2);
}

TEST(Diff, WildcardDataMatchesAnyReadBack) {
  auto g = golden("0x03000000 0xxx00xxxx\n");
  DiffResult d;
  ASSERT_TRUE(diff_datagrams({word(0x03000000, 0x15001234, true)}, g, &d).ok());
  EXPECT_EQ(marks(d), "=");
  ASSERT_TRUE(diff_datagrams({word(0x03000000, 0x15011234, true)}, g, &d).ok());
  EXPECT_EQ(marks(d), "~");
}

TEST(Diff, RepeatedPollMatchesAnyNumberOfReads) {
  auto g = golden("0x60000000\n0x61000000 {1,}\n0x63000000\n");
  std::vector<Frame> f = {word(0x60000000), word(0x61000000), word(0x61000000), word(0x61000000),
                          word(0x63000000)};
  DiffResult d;
  ASSERT_TRUE(diff_datagrams(f, g, &d).ok());
  EXPECT_EQ(marks(d), "=====");
  EXPECT_TRUE(d.same());
}

TEST(Diff, RepeatsBeyondTheMaximumAreExtra) {
  auto g = golden("0x61000000 {1,2}\n");
  DiffResult d;
  ASSERT_TRUE(diff_datagrams({word(0x61000000), word(0x61000000), word(0x61000000)}, g, &d).ok());
  EXPECT_EQ(marks(d), "==+");
}

TEST(Diff, FrameWithWrongBitCountNeverMatchesButShowsAsChangedAtItsAddress) {
  auto g = golden("0x08000064\n");
  Frame f = word(0x08000064 >> 1);
  f.bit_count = 31;
  f.flags = kFlagWrongBitCount;
  DiffResult d;
  ASSERT_TRUE(diff_datagrams({f}, g, &d).ok());
  EXPECT_EQ(marks(d), "~");
}

TEST(Diff, WithinIgnoresDatagramsBeforeAndAfterTheExpectedOnes) {
  auto g = golden("0x80000510\n0x7E010702\n");
  std::vector<Frame> f = {word(0x03000000), word(0x80000510), word(0x7E010702), word(0x03000000),
                          word(0x08000010)};
  DiffResult d;
  ASSERT_TRUE(diff_datagrams(f, g, &d, true).ok());
  EXPECT_EQ(marks(d), "==");
  EXPECT_EQ(d.ignored_before, 1);
  EXPECT_EQ(d.ignored_after, 2);
  ASSERT_TRUE(diff_datagrams(f, g, &d, false).ok());
  EXPECT_EQ(marks(d), "+==++");
}

TEST(Diff, WithinStillReportsDifferencesInside) {
  auto g = golden("0x80000510\n0x82000304\n0x7E010702\n");
  std::vector<Frame> f = {word(0x03000000), word(0x80000510), word(0x7E010702)};
  DiffResult d;
  ASSERT_TRUE(diff_datagrams(f, g, &d, true).ok());
  EXPECT_EQ(marks(d), "=-=");
}

TEST(Diff, SwappingMosiAndMisoExchangesThem) {
  auto s = swap_mosi_miso({word(1, 2, true)});
  EXPECT_EQ(s[0].mosi, 2u);
  EXPECT_EQ(s[0].miso, 1u);
}

}  // namespace
