// The hex examples in docs/protocol.md (```frames blocks) are valid frames: each parses as
// exactly one frame, its payload decodes, and re-encoding gives the same bytes.
#include <gtest/gtest.h>

#include <fstream>  // std::ifstream
#include <set>      // std::set
#include <sstream>  // std::istringstream
#include <string>   // std::string
#include <vector>   // std::vector

#include "firmware/protocol/message_table.h"  // PROTO_MESSAGE_TABLE
#include "host_tests/protocol/frame_helpers.h"
#include "host_tests/protocol/message_roundtrip.h"

#ifndef ENGRAVER_SOURCE_DIR
#error "ENGRAVER_SOURCE_DIR must point at the repository top"
#endif

namespace {

struct Example {
  test_proto::Bytes bytes;
  std::string text;
};

// Every line of every ```frames block: hex bytes before ';'.
std::vector<Example> read_examples() {
  std::ifstream doc(std::string(ENGRAVER_SOURCE_DIR) + "/docs/protocol.md");
  std::vector<Example> out;
  std::string line;
  bool inside = false;
  while (std::getline(doc, line)) {
    if (line.rfind("```frames", 0) == 0) {
      inside = true;
      continue;
    }
    if (line.rfind("```", 0) == 0) {
      inside = false;
      continue;
    }
    if (!inside) continue;
    Example e;
    e.text = line;
    std::istringstream hex(line.substr(0, line.find(';')));
    std::string byte;
    while (hex >> byte) e.bytes.push_back(static_cast<uint8_t>(std::stoul(byte, nullptr, 16)));
    out.push_back(e);
  }
  return out;
}

TEST(DocExamples, DocumentHasExamplesForEveryCommandAndReplyLetter) {
  std::set<std::string> seen;
  for (const Example& e : read_examples()) {
    if (e.bytes.size() >= 2) seen.insert(std::string(1, e.bytes[0]) + std::string(1, e.bytes[1]));
  }
  // Every row of the message table, so a new command cannot go undocumented.
  std::vector<std::string> expected;
#define DOC_CMD(Type, name, letter_value, kind, display, reply, handler, check) \
  expected.push_back(std::string("#") + char(letter_value));
#define DOC_REPLY(Type, name, letter_value, display, check) \
  expected.push_back(std::string("*") + char(letter_value));
#define DOC_SKIP(...)
  PROTO_MESSAGE_TABLE(DOC_CMD, DOC_REPLY, DOC_SKIP, DOC_SKIP, DOC_SKIP, DOC_SKIP)
#undef DOC_CMD
#undef DOC_REPLY
#undef DOC_SKIP
  ASSERT_GE(expected.size(), 20u);
  for (const std::string& letter : expected) EXPECT_EQ(1u, seen.count(letter)) << letter;
}

TEST(DocExamples, EveryExampleIsOneValidFrameThatRoundTrips) {
  const std::vector<Example> examples = read_examples();
  ASSERT_GE(examples.size(), 20u);
  for (const Example& e : examples) {
    ASSERT_FALSE(e.bytes.empty()) << e.text;
    proto::Parser parser(e.bytes[0]);
    const test_proto::Outcome out = test_proto::feed_all(parser, e.bytes);
    ASSERT_EQ(1u, out.frames.size()) << e.text;
    EXPECT_TRUE(out.rejections.empty()) << e.text;
    EXPECT_EQ(e.bytes.size(), out.frames[0].payload.size() + 6) << e.text;
    const test_proto::RoundTrip r =
        test_proto::round_trip_any(e.bytes[0], out.frames[0].letter, out.frames[0].payload.data(),
                                   static_cast<uint8_t>(out.frames[0].payload.size()));
    EXPECT_EQ(proto::ErrorCode::kOk, r.decode) << e.text;
    EXPECT_TRUE(r.same_bytes) << e.text;
  }
}

}  // namespace
