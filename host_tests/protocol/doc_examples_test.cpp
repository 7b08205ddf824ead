// The hex examples in docs/protocol.md (```frames blocks) are valid frames: each parses as
// exactly one frame, its payload decodes, and re-encoding gives the same bytes. And what the
// controller's rules fix about a reply is what its example and its text say: the seqs of an
// `*E`, the flags and numbers an `*?` describes.
#include <gtest/gtest.h>

#include <cstdio>   // std::snprintf
#include <fstream>  // std::ifstream
#include <random>   // std::mt19937
#include <set>      // std::set
#include <sstream>  // std::istringstream
#include <string>   // std::string
#include <vector>   // std::vector

#include "firmware/protocol/codec.h"          // proto::decode
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
#define DOC_CMD(Type, name, letter_value, role, display, reply, handler, check) \
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

template <typename Msg>
Msg payload_of(const Example& e) {
  Msg m{};
  EXPECT_EQ(proto::ErrorCode::kOk,
            proto::decode(e.bytes.data() + proto::kHeaderBytes, e.bytes[3], &m))
      << e.text;
  return m;
}

bool says(const Example& e, const std::string& words) {
  return e.text.find(words) != std::string::npos;
}

// docs/protocol.md section 3 and 4: an `*E` answers a frame with that frame's seq. A queued
// frame refused for its payload or its execution is not stored and does not use up its seq,
// so next_expected_seq is its own seq; a seq_gap frame is 1..7 ahead of the expected seq.
TEST(DocExamples, ErrorRepliesCarryTheSeqsTheControllerAnswersWith) {
  const std::vector<Example> examples = read_examples();
  int checked = 0;
  for (size_t i = 0; i < examples.size(); ++i) {
    const Example& e = examples[i];
    if (e.bytes.size() < 4 || e.bytes[0] != proto::kReplyStart || e.bytes[1] != proto::kReplyError)
      continue;
    const proto::ErrorReply r = payload_of<proto::ErrorReply>(e);
    const uint8_t seq = e.bytes[2];
    const int code = static_cast<int>(r.code);
    if (r.code == proto::ErrorCode::kSeqGap) {
      const uint8_t ahead = static_cast<uint8_t>(seq - r.next_expected_seq);
      EXPECT_TRUE(ahead >= 1 && ahead < proto::kWindowFrames) << e.text;
      ++checked;
      continue;
    }
    // The command it answers: the newest example before it with that seq.
    const Example* cmd = nullptr;
    for (size_t j = i; j-- > 0;) {
      const Example& c = examples[j];
      if (c.bytes.size() >= 4 && c.bytes[0] == proto::kCommandStart && c.bytes[2] == seq) {
        cmd = &c;
        break;
      }
    }
    ASSERT_NE(cmd, nullptr) << "no command example with the seq of: " << e.text;
    const bool refused_for_content = (code >= 10 && code < 20) || code >= 30;
    if (proto::command_kind(cmd->bytes[1]) == proto::FrameKind::kQueued && refused_for_content) {
      EXPECT_EQ(r.next_expected_seq, seq) << e.text;
      ++checked;
    }
  }
  EXPECT_GE(checked, 2);
}

// The `*?` example's text names each flag that is set (and no other), with the numbers the
// flags make valid, as the status table of section 3 defines them.
TEST(DocExamples, StatusExampleTextSaysWhatItsFlagsAndFieldsSay) {
  int checked = 0;
  for (const Example& e : read_examples()) {
    if (e.bytes.size() < 4 || e.bytes[0] != proto::kReplyStart || e.bytes[1] != proto::kReplyStatus)
      continue;
    ++checked;
    const proto::StatusReply r = payload_of<proto::StatusReply>(e);
    char buf[64];
    std::snprintf(buf, sizeof buf, "flags 0x%02X", r.flags);
    EXPECT_TRUE(says(e, buf)) << buf << ": " << e.text;
    const bool executed = (r.flags & proto::kStatusExecuted) != 0;
    std::snprintf(buf, sizeof buf, "done %u", r.last_executed_seq);
    EXPECT_EQ(executed, says(e, buf)) << buf << ": " << e.text;
    EXPECT_EQ(executed, says(e, "done ")) << e.text;
    const bool job = (r.flags & proto::kStatusJob) != 0;
    std::snprintf(buf, sizeof buf, "job command %ld", static_cast<long>(r.job_index));
    EXPECT_EQ(job, says(e, buf)) << buf << ": " << e.text;
    std::snprintf(buf, sizeof buf, "of job %04X", r.job_id);
    EXPECT_EQ(job, says(e, buf)) << buf << ": " << e.text;
    if (r.curve_point != 0) {
      std::snprintf(buf, sizeof buf, "curve point %u", r.curve_point);
      EXPECT_TRUE(says(e, buf)) << buf << ": " << e.text;
    }
    EXPECT_EQ((r.flags & proto::kStatusJobStarted) != 0, says(e, "under way")) << e.text;
    EXPECT_EQ((r.flags & proto::kStatusZeroed) != 0, says(e, "zeroed")) << e.text;
    EXPECT_EQ((r.flags & proto::kStatusSession) != 0, says(e, "session open")) << e.text;
    EXPECT_EQ((r.flags & proto::kStatusFramePending) != 0, says(e, "held")) << e.text;
    EXPECT_EQ((r.flags & proto::kStatusAborted) != 0, says(e, "aborted")) << e.text;
    EXPECT_EQ((r.flags & proto::kStatusLinkHold) != 0, says(e, "link")) << e.text;
    std::snprintf(buf, sizeof buf, "%u free", r.queue_free);
    EXPECT_TRUE(says(e, buf)) << buf << ": " << e.text;
    std::snprintf(buf, sizeof buf, "expects %u", r.next_expected_seq);
    EXPECT_TRUE(says(e, buf)) << buf << ": " << e.text;
    std::snprintf(buf, sizeof buf, "%u %%", r.override_percent);
    EXPECT_TRUE(says(e, buf)) << buf << ": " << e.text;
  }
  EXPECT_GE(checked, 1);
}

// The typed decoder of the command with that letter, as decode_command must answer.
proto::ErrorCode typed_decode(uint8_t letter, const uint8_t* payload, uint8_t length,
                              proto::AnyCommand* msg) {
#define DOC_DECODE(Type, name, letter_value, role, display, reply, handler, check) \
  if (letter == (letter_value)) return proto::decode(payload, length, &msg->m_##Type);
#define DOC_SKIP(...)
  PROTO_MESSAGE_TABLE(DOC_DECODE, DOC_SKIP, DOC_SKIP, DOC_SKIP, DOC_SKIP, DOC_SKIP)
#undef DOC_DECODE
  return proto::ErrorCode::kUnknownCommand;
}

// The decoded command's fields as the typed encoder writes them (padding left out).
test_proto::Bytes encoded_as(uint8_t letter, const proto::AnyCommand& msg) {
  proto::Payload p;
  p.length = 0;
#define DOC_ENCODE(Type, name, letter_value, role, display, reply, handler, check) \
  if (letter == (letter_value)) EXPECT_EQ(proto::ErrorCode::kOk, proto::encode(msg.m_##Type, &p));
  PROTO_MESSAGE_TABLE(DOC_ENCODE, DOC_SKIP, DOC_SKIP, DOC_SKIP, DOC_SKIP, DOC_SKIP)
#undef DOC_ENCODE
#undef DOC_SKIP
  return test_proto::Bytes(p.bytes, p.bytes + p.length);
}

// The application decodes every command through the one table walker, decode_command: on
// each command example of the document and on 2 000 mutants of each (bytes changed, cut,
// lengthened), it gives the typed decoder's code and the same fields.
TEST(DocExamples, DecodeCommandDecodesEveryCommandAsItsTypedDecoder) {
  std::mt19937 rng(22);
  int ok = 0;
  int refused = 0;
  for (const Example& e : read_examples()) {
    if (e.bytes.size() < proto::kHeaderBytes || e.bytes[0] != proto::kCommandStart) continue;
    const uint8_t letter = e.bytes[1];
    const test_proto::Bytes example(e.bytes.begin() + proto::kHeaderBytes,
                                    e.bytes.begin() + proto::kHeaderBytes + e.bytes[3]);
    for (int trial = 0; trial <= 2000; ++trial) {
      test_proto::Bytes payload = example;
      if (trial % 4 == 1 && !payload.empty()) payload[rng() % payload.size()] ^= 1u << (rng() % 8);
      if (trial % 4 == 2 && !payload.empty()) payload[rng() % payload.size()] = rng() & 0xFF;
      if (trial % 4 == 3) payload.resize(rng() % (proto::kMaxPayload + 1), rng() & 3);
      const uint8_t n = static_cast<uint8_t>(payload.size());
      proto::AnyCommand want;
      const proto::ErrorCode code = typed_decode(letter, payload.data(), n, &want);
      proto::AnyCommand got;
      ASSERT_EQ(code, proto::decode_command(letter, payload.data(), n, &got)) << e.text;
      if (code != proto::ErrorCode::kOk) {
        ++refused;
        continue;
      }
      ++ok;
      EXPECT_EQ(payload, encoded_as(letter, got)) << e.text << " trial " << trial;
      EXPECT_EQ(encoded_as(letter, want), encoded_as(letter, got)) << e.text << " trial " << trial;
    }
  }
  EXPECT_GT(ok, 2000);
  EXPECT_GT(refused, 2000);
  proto::AnyCommand m;
  EXPECT_EQ(proto::ErrorCode::kUnknownCommand, proto::decode_command('O', nullptr, 0, &m));
}

}  // namespace
