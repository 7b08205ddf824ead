// Frame parser: byte-by-byte and chunked input, garbage, corruption, resynchronisation.
#include "firmware/protocol/parser.h"

#include <gtest/gtest.h>

#include <random>  // std::mt19937

#include "host_tests/protocol/frame_helpers.h"

namespace {

using proto::ErrorCode;
using proto::Parser;
using test_proto::Bytes;
using test_proto::concat;
using test_proto::feed_all;
using test_proto::Outcome;
using test_proto::raw_frame;

const uint8_t kHash = proto::kCommandStart;

Bytes move_frame(uint8_t seq) {
  proto::FeedMoveCmd m = {12000, -3500, 2000};
  return test_proto::message_frame(m, seq);
}

TEST(Parser, FrameFedByteByByteIsDeliveredOnceWithItsFields) {
  Parser parser(kHash);
  const Outcome out = feed_all(parser, raw_frame(kHash, 'G', 7, {1, 2, 3}));
  ASSERT_EQ(1u, out.frames.size());
  EXPECT_EQ('G', out.frames[0].letter);
  EXPECT_EQ(7, out.frames[0].seq);
  EXPECT_EQ(Bytes({1, 2, 3}), out.frames[0].payload);
  EXPECT_TRUE(out.rejections.empty());
}

TEST(Parser, EmptyPayloadFrameIsSixBytesAndParses) {
  Parser parser(kHash);
  const Bytes f = raw_frame(kHash, '?', 0, {});
  ASSERT_EQ(6u, f.size());
  EXPECT_EQ(1u, feed_all(parser, f).frames.size());
}

TEST(Parser, FrameKindComesFromTheLetter) {
  Parser parser(kHash);
  const Bytes f = concat({raw_frame(kHash, 'H', 1, {}), raw_frame(kHash, 'D', 2, {0})});
  proto::FrameKind kinds[2];
  int n = 0;
  for (uint8_t b : f) {
    for (proto::ParseEvent ev = parser.feed(b); ev != proto::ParseEvent::kNone;
         ev = parser.poll()) {
      if (ev == proto::ParseEvent::kFrame && n < 2) kinds[n++] = parser.frame().kind;
    }
  }
  ASSERT_EQ(2, n);
  EXPECT_EQ(proto::FrameKind::kRealtime, kinds[0]);
  EXPECT_EQ(proto::FrameKind::kQueued, kinds[1]);
}

TEST(Parser, BackToBackFramesAllArrive) {
  Parser parser(kHash);
  const Outcome out = feed_all(parser, concat({move_frame(1), move_frame(2), move_frame(3)}));
  ASSERT_EQ(3u, out.frames.size());
  EXPECT_EQ(3, out.frames[2].seq);
}

TEST(Parser, RandomChunkBoundariesDoNotMatter) {
  std::mt19937 rng(1234);
  std::vector<Bytes> parts;
  for (int i = 0; i < 50; ++i) parts.push_back(move_frame(static_cast<uint8_t>(i)));
  const Bytes stream = concat(parts);
  Parser parser(kHash);
  Outcome out;
  size_t at = 0;
  while (at < stream.size()) {
    const size_t chunk = std::min<size_t>(1 + rng() % 97, stream.size() - at);
    for (size_t i = 0; i < chunk; ++i) test_proto::drain(parser, parser.feed(stream[at + i]), &out);
    at += chunk;
  }
  ASSERT_EQ(50u, out.frames.size());
  for (int i = 0; i < 50; ++i) EXPECT_EQ(i, out.frames[i].seq);
}

TEST(Parser, GarbageBetweenFramesIsSkippedAndCounted) {
  Parser parser(kHash);
  const Bytes garbage = {0x00, 0xFF, 'G', 0x10, 0x7E, 0x0A};
  const Outcome out = feed_all(parser, concat({garbage, move_frame(1), garbage, move_frame(2)}));
  EXPECT_EQ(2u, out.frames.size());
  EXPECT_TRUE(out.rejections.empty());
  EXPECT_EQ(12, parser.skipped_bytes());
}

TEST(Parser, RandomGarbageBetweenFramesNeverLosesAFrame) {
  std::mt19937 rng(99);
  std::vector<Bytes> parts;
  for (int i = 0; i < 200; ++i) {
    Bytes g(rng() % 20);
    for (uint8_t& b : g) b = static_cast<uint8_t>(rng());
    parts.push_back(g);
    parts.push_back(move_frame(static_cast<uint8_t>(i)));
  }
  Parser parser(kHash);
  const Outcome out = feed_all(parser, concat(parts));
  // Garbage may contain '#' + valid-looking headers, but never a valid CRC by chance here.
  ASSERT_EQ(200u, out.frames.size());
  for (int i = 0; i < 200; ++i) EXPECT_EQ(static_cast<uint8_t>(i), out.frames[i].seq);
}

TEST(Parser, EveryIntactFrameSurvivesNeighboursDamagedByFlipsCutsAndInsertedStartBytes) {
  // 1000 frames; about half damaged: a bit flip, cut short, or a '#'+header inserted. The
  // damage never leaves the original bytes rebuildable (a cut never removes a tail that
  // starts with '#', which the next frame's start byte would restore; a header is never
  // inserted before a '#' nor ends in '#'), so: every intact frame arrives, in order, and
  // nothing else (barring a 1-in-65536 CRC coincidence on a false candidate).
  std::mt19937 rng(2024);
  std::vector<Bytes> parts;
  std::vector<int> intact;
  for (int i = 0; i < 1000; ++i) {
    const uint8_t seq = static_cast<uint8_t>(i);
    Bytes f = (i % 3 == 0) ? raw_frame(kHash, 'D', seq, Bytes(rng() % 65, kHash)) : move_frame(seq);
    switch (rng() % 6) {
      case 0:
        f[1 + rng() % (f.size() - 1)] ^= static_cast<uint8_t>(1u << (rng() % 8));
        break;
      case 1: {
        size_t keep = 1 + rng() % (f.size() - 1);
        while (f[keep] == kHash) --keep;
        f.resize(keep);
        break;
      }
      case 2: {
        const Bytes fake = {kHash, 'G', 0, static_cast<uint8_t>(rng() % 32)};
        size_t at = 1 + rng() % (f.size() - 1);
        while (f[at] == kHash) --at;
        f.insert(f.begin() + at, fake.begin(), fake.end());
        break;
      }
      default:
        intact.push_back(i);
    }
    parts.push_back(f);
  }
  Parser parser(kHash);
  Outcome out = feed_all(parser, concat(parts));
  // The line goes quiet: the last frames may still sit inside a long false candidate.
  test_proto::drain(parser, parser.expire(), &out);
  ASSERT_EQ(intact.size(), out.frames.size());
  for (size_t k = 0; k < intact.size(); ++k) {
    EXPECT_EQ(static_cast<uint8_t>(intact[k]), out.frames[k].seq);
  }
  EXPECT_GT(intact.size(), 400u);
}

TEST(Parser, CorruptedCrcIsRejectedWithBadCrcAndCounted) {
  Parser parser(kHash);
  Bytes f = move_frame(5);
  f.back() ^= 0x01;
  const Outcome out = feed_all(parser, f);
  EXPECT_TRUE(out.frames.empty());
  ASSERT_EQ(1u, out.rejections.size());
  EXPECT_EQ(ErrorCode::kBadCrc, out.rejections[0]);
  EXPECT_EQ(1, parser.error_count(ErrorCode::kBadCrc));
  EXPECT_EQ(1, parser.rejected_total());
}

TEST(Parser, CorruptedPayloadByteIsRejectedAndTheNextFrameStillArrives) {
  Parser parser(kHash);
  Bytes bad = move_frame(5);
  bad[6] ^= 0x40;
  const Outcome out = feed_all(parser, concat({bad, move_frame(6)}));
  ASSERT_EQ(1u, out.frames.size());
  EXPECT_EQ(6, out.frames[0].seq);
  EXPECT_EQ(std::vector<ErrorCode>({ErrorCode::kBadCrc}), out.rejections);
}

TEST(Parser, OversizeLengthIsRejectedAtTheLengthByte) {
  Parser parser(kHash);
  const Bytes header = {kHash, 'G', 1, proto::kMaxPayload + 1};
  const Outcome out = feed_all(parser, header);
  EXPECT_EQ(std::vector<ErrorCode>({ErrorCode::kLengthTooLarge}), out.rejections);
  EXPECT_FALSE(parser.in_frame());
}

TEST(Parser, MaximumPayloadOf64BytesIsAccepted) {
  Parser parser(kHash);
  const Outcome out = feed_all(parser, raw_frame(kHash, 'D', 1, Bytes(64, 0x23)));
  ASSERT_EQ(1u, out.frames.size());
  EXPECT_EQ(64u, out.frames[0].payload.size());
}

TEST(Parser, NonLetterAfterStartByteIsRejectedAtOnce) {
  Parser parser(kHash);
  const Outcome out = feed_all(parser, concat({{kHash, 0x01}, move_frame(3)}));
  EXPECT_EQ(std::vector<ErrorCode>({ErrorCode::kBadLetter}), out.rejections);
  ASSERT_EQ(1u, out.frames.size());
}

TEST(Parser, DoubledStartByteDoesNotCostTheFrame) {
  Parser parser(kHash);
  const Outcome out = feed_all(parser, concat({{kHash}, move_frame(3)}));
  ASSERT_EQ(1u, out.frames.size());
  EXPECT_EQ(3, out.frames[0].seq);
}

TEST(Parser, TruncatedFrameFollowedByAFullFrameLosesOnlyTheTruncatedOne) {
  // The truncated frame's length makes the parser swallow the next frame's bytes; the CRC
  // fails and the re-scan finds the real frame inside the swallowed bytes.
  Parser parser(kHash);
  Bytes cut = move_frame(1);
  cut.resize(8);
  const Outcome out = feed_all(parser, concat({cut, move_frame(2), move_frame(3)}));
  ASSERT_EQ(2u, out.frames.size());
  EXPECT_EQ(2, out.frames[0].seq);
  EXPECT_EQ(3, out.frames[1].seq);
  EXPECT_EQ(std::vector<ErrorCode>({ErrorCode::kBadCrc}), out.rejections);
}

TEST(Parser, CorruptedLengthThatSwallowsTheNextFrameIsRecoveredByRescan) {
  Parser parser(kHash);
  Bytes bad = raw_frame(kHash, 'S', 1, {0, 'h', 'i'});
  bad[3] = 60;  // claims 60 payload bytes
  const Outcome out =
      feed_all(parser, concat({bad, move_frame(2), move_frame(3), move_frame(4), move_frame(5)}));
  ASSERT_EQ(4u, out.frames.size());
  EXPECT_EQ(2, out.frames[0].seq);
  EXPECT_EQ(5, out.frames[3].seq);
}

TEST(Parser, FalseStartByteInsidePayloadOfCorruptedFrameDoesNotCostTheNextFrame) {
  Parser parser(kHash);
  // A payload full of '#' followed by 'G', seq, small length: looks like headers.
  Bytes bad = raw_frame(kHash, 'D', 1, {kHash, 'G', 9, 2, kHash, kHash});
  bad[bad.size() - 1] ^= 0xFF;  // break the CRC
  const Outcome out = feed_all(parser, concat({bad, move_frame(2)}));
  ASSERT_EQ(1u, out.frames.size());
  EXPECT_EQ(2, out.frames[0].seq);
  EXPECT_GE(out.rejections.size(), 1u);
}

TEST(Parser, FrameHiddenInsideACorruptedFramesPayloadIsFound) {
  // A complete valid frame sits inside the payload of a frame whose CRC is broken: after
  // the outer frame fails, the re-scan delivers the inner one.
  Parser parser(kHash);
  const Bytes inner = raw_frame(kHash, 'H', 42, {});
  Bytes outer = raw_frame(kHash, 'D', 1, inner);
  outer.back() ^= 0x55;
  const Outcome out = feed_all(parser, outer);
  ASSERT_EQ(1u, out.frames.size());
  EXPECT_EQ('H', out.frames[0].letter);
  EXPECT_EQ(42, out.frames[0].seq);
}

TEST(Parser, ExpireDropsAPartialFrameAsTruncated) {
  Parser parser(kHash);
  Bytes cut = move_frame(1);
  cut.resize(5);
  feed_all(parser, cut);
  EXPECT_TRUE(parser.in_frame());
  Outcome out;
  test_proto::drain(parser, parser.expire(), &out);
  EXPECT_EQ(std::vector<ErrorCode>({ErrorCode::kTruncated}), out.rejections);
  EXPECT_FALSE(parser.in_frame());
  EXPECT_EQ(1u, feed_all(parser, move_frame(2)).frames.size());
}

TEST(Parser, ExpireDeliversAFrameFoundInsideTheStaleBytesAndDropsTheRest) {
  // '#D' claiming 60 bytes, then a complete #H frame, then a lone '#G' start: after the
  // silence the #H is delivered and both partial candidates are dropped as truncated.
  Parser parser(kHash);
  feed_all(parser, concat({{kHash, 'D', 1, 60}, raw_frame(kHash, 'H', 4, {}), {kHash, 'G'}}));
  Outcome out;
  test_proto::drain(parser, parser.expire(), &out);
  ASSERT_EQ(1u, out.frames.size());
  EXPECT_EQ('H', out.frames[0].letter);
  EXPECT_EQ(std::vector<ErrorCode>({ErrorCode::kTruncated, ErrorCode::kTruncated}), out.rejections);
  EXPECT_FALSE(parser.in_frame());
}

TEST(Parser, ExpireWithNothingBufferedDoesNothing) {
  Parser parser(kHash);
  EXPECT_EQ(proto::ParseEvent::kNone, parser.expire());
  EXPECT_EQ(0, parser.rejected_total());
}

TEST(Parser, RxErrorsAreCountedAsOverrun) {
  Parser parser(kHash);
  parser.note_rx_error();
  parser.note_rx_error();
  EXPECT_EQ(2, parser.error_count(ErrorCode::kRxOverrun));
  EXPECT_EQ(ErrorCode::kRxOverrun, parser.last_error());
}

TEST(Parser, ReplyParserIgnoresCommandFrames) {
  Parser parser(proto::kReplyStart);
  proto::AckReply ack = {3};
  const Outcome out = feed_all(parser, concat({move_frame(1), test_proto::message_frame(ack, 1)}));
  ASSERT_EQ(1u, out.frames.size());
  EXPECT_EQ('O', out.frames[0].letter);
}

TEST(Parser, CommandFrameWithReplyStartByteFailsTheCrcCheck) {
  // The start byte is covered by the CRC: a frame cannot change direction by one bit flip.
  Bytes f = move_frame(1);
  f[0] = proto::kReplyStart;
  Parser parser(proto::kReplyStart);
  const Outcome out = feed_all(parser, f);
  EXPECT_TRUE(out.frames.empty());
  EXPECT_EQ(std::vector<ErrorCode>({ErrorCode::kBadCrc}), out.rejections);
}

TEST(Parser, IgnoringFeedResultsLeavesTheParserUsable) {
  // Misuse: feed() results ignored. The parser must stay within its buffer and keep working.
  Parser parser(kHash);
  Bytes stream(1000, kHash);
  for (uint8_t b : stream) parser.feed(b);
  Outcome out;
  test_proto::drain(parser, parser.poll(), &out);
  for (int i = 0; i < 3; ++i) test_proto::drain(parser, parser.expire(), &out);
  const Outcome good = feed_all(parser, concat({Bytes(80, 0), move_frame(9)}));
  ASSERT_EQ(1u, good.frames.size());
  EXPECT_EQ(9, good.frames[0].seq);
}

TEST(Parser, CountersSaturateInsteadOfWrapping) {
  Parser parser(kHash);
  for (int i = 0; i < 70000; ++i) parser.note_rx_error();
  EXPECT_EQ(0xFFFF, parser.error_count(ErrorCode::kRxOverrun));
  EXPECT_EQ(0xFFFF, parser.rejected_total());
}

}  // namespace
