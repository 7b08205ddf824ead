// Payload codecs: byte layout, round trips for every message, malformed payloads rejected.
#include "firmware/protocol/codec.h"

#include <gtest/gtest.h>

#include <cstring>  // memcmp

#include "host_tests/protocol/frame_helpers.h"

namespace {

using proto::ErrorCode;
using proto::Payload;
using test_proto::Bytes;

template <typename Msg>
Bytes encoded(const Msg& m) {
  Payload p;
  EXPECT_EQ(ErrorCode::kOk, proto::encode(m, &p));
  return Bytes(p.bytes, p.bytes + p.length);
}

template <typename Msg>
ErrorCode decode_bytes(const Bytes& b, Msg* m) {
  return proto::decode(b.data(), static_cast<uint8_t>(b.size()), m);
}

// Encode -> decode -> encode gives the same bytes (field-by-field equality via bytes).
template <typename Msg>
void expect_round_trip(const Msg& m) {
  const Bytes first = encoded(m);
  Msg back;
  ASSERT_EQ(ErrorCode::kOk, decode_bytes(first, &back));
  EXPECT_EQ(first, encoded(back));
}

template <typename Msg>
ErrorCode encode_error(const Msg& m) {
  Payload p;
  return proto::encode(m, &p);
}

// ---- byte layouts written out by hand from docs/protocol.md ----

TEST(CodecLayout, FeedMoveIsXYLittleEndianThenFeed) {
  proto::FeedMoveCmd m = {12000, -3500, 2000};
  EXPECT_EQ(Bytes({0xE0, 0x2E, 0x00, 0x00, 0x54, 0xF2, 0xFF, 0xFF, 0xD0, 0x07}), encoded(m));
}

TEST(CodecLayout, SplineHeaderIsDegreeRationalCountsFeedOffset) {
  proto::SplineHeaderCmd m = {3, true, 5, 9, 1500, -2};
  EXPECT_EQ(Bytes({3, 0x01, 5, 0, 9, 0, 0xDC, 0x05, 0xFE, 0xFF, 0xFF, 0xFF}), encoded(m));
}

TEST(CodecLayout, SplineDataIsIndicesThenPointsThenKnots) {
  proto::SplineDataCmd m = {};
  m.control_index = 2;
  m.control_n = 1;
  m.knot_index = 4;
  m.knot_n = 1;
  m.control[0].x_um = 1;
  m.control[0].y_um = -1;
  m.control[0].weight_q14 = 16384;
  m.knot[0] = 0x01020304;
  EXPECT_EQ(Bytes({2, 1, 4, 1, 1, 0, 0, 0, 0xFF, 0xFF, 0xFF, 0xFF, 0x00, 0x40, 4, 3, 2, 1}),
            encoded(m));
}

TEST(CodecLayout, StatusReplyIs31BytesWithTheJobProgressLast) {
  proto::StatusReply s = {};
  s.override_percent = 100;
  s.job_index = 0x01020304;
  s.curve_point = 0x0506;
  s.job_id = 0x0708;
  const Bytes b = encoded(s);
  ASSERT_EQ(31u, b.size());
  EXPECT_EQ(Bytes({4, 3, 2, 1, 6, 5, 8, 7}), Bytes(b.begin() + 23, b.end()));
}

TEST(CodecLayout, JobMarkIsIndexThenFirstPoint) {
  EXPECT_EQ(Bytes({4, 3, 2, 1, 6, 5, 8, 7}),
            encoded(proto::JobMarkCmd{0x01020304, 0x0506, 0x0708}));
  proto::JobMarkCmd m;
  EXPECT_EQ(ErrorCode::kFieldRange, decode_bytes(Bytes({0, 0, 0, 0x80, 0, 0, 0, 0}), &m));
}

TEST(CodecLayout, TextIsRowThenCharacters) {
  proto::TextCmd t = {1, 2, {'O', 'K'}};
  EXPECT_EQ(Bytes({1, 'O', 'K'}), encoded(t));
}

// ---- round trips of every message ----

TEST(CodecRoundTrip, EveryCommand) {
  expect_round_trip(proto::SessionCmd{1});
  expect_round_trip(proto::StatusCmd{});
  expect_round_trip(proto::HoldCmd{});
  expect_round_trip(proto::ResumeCmd{});
  expect_round_trip(proto::AbortCmd{});
  expect_round_trip(proto::ClearAlarmCmd{});
  expect_round_trip(proto::OverrideCmd{150});
  expect_round_trip(proto::TextCmd{
      0, 16, {'0', '1', '2', '3', '4', '5', '6', '7', '8', '9', 'a', 'b', 'c', 'd', 'e', '~'}});
  expect_round_trip(proto::TextCmd{1, 0, {}});
  expect_round_trip(proto::SplineHeaderCmd{1, false, 2, 4, 1});
  expect_round_trip(proto::SplineHeaderCmd{3, true, 64, 68, 65535});
  expect_round_trip(proto::SplineHeaderCmd{3, false, 4, 8, 1000, -100000});
  expect_round_trip(proto::SplineHeaderCmd{3, false, 4, 8, 1000, 100000});
  expect_round_trip(proto::ResolutionCmd{50, 5});
  expect_round_trip(proto::FeedMoveCmd{-1000000, 1000000, 65535});
  expect_round_trip(proto::RapidMoveCmd{0, -1});
  expect_round_trip(proto::ZMoveCmd{-2000, 300});
  expect_round_trip(proto::ZeroingCmd{7});
  expect_round_trip(proto::PauseCmd{
      16, {'C', 'h', 'a', 'n', 'g', 'e', ' ', 't', 'o', 'o', 'l', ' ', 'T', '2', ' ', '~'}});
  expect_round_trip(proto::PauseCmd{0, {}});
  expect_round_trip(proto::DwellCmd{1});
  expect_round_trip(proto::DwellCmd{65535});
  expect_round_trip(proto::SpindleCmd{0});
  expect_round_trip(proto::SpindleCmd{1});
  expect_round_trip(proto::DrillCmd{-1000000, 1000000, 1000000, -1000000, 1});
  expect_round_trip(proto::DrillCmd{12000, 34000, 500, 499, 65535});
  expect_round_trip(proto::JobMarkCmd{0, 0, 0});
  expect_round_trip(proto::JobMarkCmd{2147483647, 65535, 65535});
}

TEST(CodecLayout, NewMachineCommandsAreLittleEndianInFieldOrder) {
  EXPECT_EQ(encoded(proto::PauseCmd{2, {'O', 'K'}}), Bytes({'O', 'K'}));
  EXPECT_EQ(encoded(proto::DwellCmd{0x1234}), Bytes({0x34, 0x12}));
  EXPECT_EQ(encoded(proto::SpindleCmd{1}), Bytes({1}));
  EXPECT_EQ(encoded(proto::DrillCmd{1, -1, 0x0100, -2, 0x0203}),
            Bytes({1, 0, 0, 0, 0xFF, 0xFF, 0xFF, 0xFF, 0, 1, 0, 0, 0xFE, 0xFF, 0xFF, 0xFF, 3, 2}));
}

TEST(CodecRoundTrip, SplineDataAtEveryPackingThatFits64Bytes) {
  int packings = 0;
  for (uint8_t nc = 0; nc <= proto::kMaxDataControls; ++nc) {
    for (uint8_t nk = 0; nk <= proto::kMaxDataKnots; ++nk) {
      if (nc + nk == 0 || 4 + 10 * nc + 4 * nk > 64) continue;
      proto::SplineDataCmd m = {};
      m.control_index = static_cast<uint8_t>(64 - nc);
      m.control_n = nc;
      m.knot_index = static_cast<uint8_t>(68 - nk);
      m.knot_n = nk;
      for (int i = 0; i < nc; ++i) {
        m.control[i].x_um = -1000000 + i * 12345;
        m.control[i].y_um = 1000000 - i * 777;
        m.control[i].weight_q14 = static_cast<uint16_t>(1 + i * 9000);
      }
      for (int i = 0; i < nk; ++i) m.knot[i] = -2147483647 - 1 + i * 1000000;
      expect_round_trip(m);
      EXPECT_EQ(static_cast<size_t>(4 + 10 * nc + 4 * nk), encoded(m).size());
      ++packings;
    }
  }
  EXPECT_EQ(57, packings);
}

TEST(CodecRoundTrip, EveryReply) {
  expect_round_trip(proto::AckReply{0, 0, false});
  expect_round_trip(proto::AckReply{255, 2, true});
  expect_round_trip(proto::ErrorReply{ErrorCode::kGeometry, 5, 17});
  expect_round_trip(
      proto::SessionReply{2, 64, 8, 16, 256, 3, 64, 0, 2, 297000, 210000, 40000, 25000, 5000});
  proto::StatusReply s = {proto::MachineState::kHeld,
                          proto::Alarm::kNone,
                          0x06,
                          100,
                          3,
                          40,
                          37,
                          ErrorCode::kBadCrc,
                          297000,
                          -1,
                          -40000,
                          65535,
                          1};
  expect_round_trip(s);
  expect_round_trip(proto::AlarmReply{proto::Alarm::kLimitSwitch, proto::MachineState::kAlarm});
}

// ---- wrong payload length ----

TEST(CodecMalformed, EveryFixedSizeMessageRejectsOneByteMoreAndOneLess) {
  // Each case: a correct payload; adding or removing a byte must give kPayloadLength.
  const Bytes zeros(40, 0);
  const auto check = [&](auto msg, size_t size) {
    using Msg = decltype(msg);
    Msg m;
    if (size > 0) {
      EXPECT_EQ(ErrorCode::kPayloadLength,
                decode_bytes(Bytes(zeros.begin(), zeros.begin() + size - 1), &m))
          << "letter " << static_cast<char>(Msg::kLetter);
    }
    EXPECT_EQ(ErrorCode::kPayloadLength,
              decode_bytes(Bytes(zeros.begin(), zeros.begin() + size + 1), &m))
        << "letter " << static_cast<char>(Msg::kLetter);
  };
  check(proto::SessionCmd{}, 1);
  check(proto::StatusCmd{}, 0);
  check(proto::HoldCmd{}, 0);
  check(proto::ResumeCmd{}, 0);
  check(proto::AbortCmd{}, 0);
  check(proto::ClearAlarmCmd{}, 0);
  check(proto::OverrideCmd{}, 1);
  check(proto::SplineHeaderCmd{}, 12);
  check(proto::ResolutionCmd{}, 4);
  check(proto::FeedMoveCmd{}, 10);
  check(proto::RapidMoveCmd{}, 8);
  check(proto::ZMoveCmd{}, 6);
  check(proto::ZeroingCmd{}, 1);
  check(proto::DwellCmd{}, 2);
  check(proto::SpindleCmd{}, 1);
  check(proto::DrillCmd{}, 18);
  check(proto::JobMarkCmd{}, 8);
  check(proto::AckReply{}, 3);
  check(proto::ErrorReply{}, 3);
  check(proto::SessionReply{}, 26);
  check(proto::StatusReply{}, 31);
  check(proto::AlarmReply{}, 2);
}

TEST(CodecMalformed, TextLongerThan16CharactersOrEmptyIsRejected) {
  proto::TextCmd t;
  EXPECT_EQ(ErrorCode::kPayloadLength, decode_bytes(Bytes(18, 'a'), &t));
  EXPECT_EQ(ErrorCode::kPayloadLength, decode_bytes(Bytes(), &t));
}

TEST(CodecMalformed, SplineDataLengthMustMatchItsCounts) {
  proto::SplineDataCmd d;
  EXPECT_EQ(ErrorCode::kPayloadLength, decode_bytes(Bytes({0, 1, 0, 0}), &d));  // 1 point, no bytes
  EXPECT_EQ(ErrorCode::kPayloadLength, decode_bytes(Bytes({0, 0, 0, 1, 1, 2, 3}), &d));
  EXPECT_EQ(ErrorCode::kPayloadLength, decode_bytes(Bytes({0, 0, 0}), &d));
}

TEST(CodecMalformed, NullBytesWithNonZeroLengthIsALengthError) {
  proto::FeedMoveCmd m;
  EXPECT_EQ(ErrorCode::kPayloadLength, proto::decode(nullptr, 10, &m));
}

// ---- out-of-range fields (decode and encode agree) ----

template <typename Msg>
void expect_range_error(const Bytes& payload) {
  Msg m;
  EXPECT_EQ(ErrorCode::kFieldRange, decode_bytes(payload, &m))
      << "letter " << static_cast<char>(Msg::kLetter);
}

TEST(CodecMalformed, SessionVersionZeroIsOutOfRange) {
  expect_range_error<proto::SessionCmd>({0});
}

TEST(CodecMalformed, OverrideOutside10To200IsOutOfRange) {
  expect_range_error<proto::OverrideCmd>({9});
  expect_range_error<proto::OverrideCmd>({201});
  proto::OverrideCmd ok;
  EXPECT_EQ(ErrorCode::kOk, decode_bytes(Bytes({10}), &ok));
  EXPECT_EQ(ErrorCode::kOk, decode_bytes(Bytes({200}), &ok));
}

TEST(CodecMalformed, TextRowAbove1OrNonPrintableCharacterIsOutOfRange) {
  expect_range_error<proto::TextCmd>({2, 'a'});
  expect_range_error<proto::TextCmd>({0, 'a', 0x1F});
  expect_range_error<proto::TextCmd>({0, 0x7F});
}

TEST(CodecMalformed, SplineHeaderFieldsOutOfRange) {
  expect_range_error<proto::SplineHeaderCmd>({0, 0, 2, 0, 3, 0, 1, 0, 0, 0, 0, 0});   // degree 0
  expect_range_error<proto::SplineHeaderCmd>({4, 0, 5, 0, 10, 0, 1, 0, 0, 0, 0, 0});  // degree 4
  expect_range_error<proto::SplineHeaderCmd>(
      {3, 2, 4, 0, 8, 0, 1, 0, 0, 0, 0, 0});  // unknown flag bit
  expect_range_error<proto::SplineHeaderCmd>(
      {3, 0, 3, 0, 7, 0, 1, 0, 0, 0, 0, 0});  // too few points
  expect_range_error<proto::SplineHeaderCmd>({1, 0, 65, 0, 67, 0, 1, 0, 0, 0, 0, 0});  // 65 points
  expect_range_error<proto::SplineHeaderCmd>(
      {2, 0, 4, 0, 8, 0, 1, 0, 0, 0, 0, 0});  // knots != 4+2+1
  expect_range_error<proto::SplineHeaderCmd>({2, 0, 4, 0, 7, 0, 0, 0, 0, 0, 0, 0});  // feed 0
  // tool offset 100001 um
  expect_range_error<proto::SplineHeaderCmd>({2, 0, 4, 0, 7, 0, 1, 0, 0xA1, 0x86, 0x01, 0});
}

TEST(CodecMalformed, SplineDataFieldsOutOfRange) {
  // No content at all.
  expect_range_error<proto::SplineDataCmd>({0, 0, 0, 0});
  // Seven control points do not fit 64 bytes.
  expect_range_error<proto::SplineDataCmd>({0, 7, 0, 0});
  // Sixteen knots do not fit.
  expect_range_error<proto::SplineDataCmd>({0, 0, 0, 16});
  // Knot index 67 + 2 knots passes the last knot (68).
  expect_range_error<proto::SplineDataCmd>({0, 0, 67, 2, 0, 0, 0, 0, 0, 0, 0, 0});
  // Control index 64 + 1 point passes the last control point.
  expect_range_error<proto::SplineDataCmd>({64, 1, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0x40});
  // Weight zero.
  expect_range_error<proto::SplineDataCmd>({0, 1, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0});
  // x = 1000001 um.
  expect_range_error<proto::SplineDataCmd>({0, 1, 0, 0, 0x41, 0x42, 0x0F, 0, 0, 0, 0, 0, 0, 0x40});
}

TEST(CodecMalformed, CoordinatesBeyondOneMetreAreOutOfRange) {
  // 1000001 = 0x000F4241; -1000001 = 0xFFF0BDBF.
  expect_range_error<proto::FeedMoveCmd>({0x41, 0x42, 0x0F, 0, 0, 0, 0, 0, 1, 0});
  expect_range_error<proto::RapidMoveCmd>({0, 0, 0, 0, 0xBF, 0xBD, 0xF0, 0xFF});
  expect_range_error<proto::ZMoveCmd>({0x41, 0x42, 0x0F, 0, 1, 0});
  proto::RapidMoveCmd edge;
  EXPECT_EQ(ErrorCode::kOk,
            decode_bytes(Bytes({0x40, 0x42, 0x0F, 0, 0xC0, 0xBD, 0xF0, 0xFF}), &edge));
  EXPECT_EQ(1000000, edge.x_um);
  EXPECT_EQ(-1000000, edge.y_um);
}

TEST(CodecMalformed, ZeroFeedsAndTolerancesAreOutOfRange) {
  expect_range_error<proto::FeedMoveCmd>({0, 0, 0, 0, 0, 0, 0, 0, 0, 0});
  expect_range_error<proto::ZMoveCmd>({0, 0, 0, 0, 0, 0});
  expect_range_error<proto::ResolutionCmd>({0, 0, 1, 0});
  expect_range_error<proto::ResolutionCmd>({1, 0, 0, 0});
}

TEST(CodecMalformed, PauseTextIsAtMost16PrintableCharacters) {
  proto::PauseCmd p;
  EXPECT_EQ(ErrorCode::kPayloadLength, decode_bytes(Bytes(17, 'a'), &p));
  EXPECT_EQ(ErrorCode::kOk, decode_bytes(Bytes(16, 'a'), &p));
  expect_range_error<proto::PauseCmd>({'a', 0x7F});
  expect_range_error<proto::PauseCmd>({0x1F});
}

TEST(CodecMalformed, DwellOfZeroAndSpindleOtherThanZeroOrOneAreOutOfRange) {
  expect_range_error<proto::DwellCmd>({0, 0});
  expect_range_error<proto::SpindleCmd>({2});
}

TEST(CodecMalformed, DrillBottomMustBeBelowItsStartAndItsFeedNonZero) {
  // x 0, y 0, start 100, bottom 100 (not below), feed 1.
  expect_range_error<proto::DrillCmd>({0, 0, 0, 0, 0, 0, 0, 0, 100, 0, 0, 0, 100, 0, 0, 0, 1, 0});
  // start 100, bottom 99, feed 0.
  expect_range_error<proto::DrillCmd>({0, 0, 0, 0, 0, 0, 0, 0, 100, 0, 0, 0, 99, 0, 0, 0, 0, 0});
  // x 1000001.
  expect_range_error<proto::DrillCmd>(
      {0x41, 0x42, 0x0F, 0, 0, 0, 0, 0, 100, 0, 0, 0, 99, 0, 0, 0, 1, 0});
  proto::DrillCmd ok;
  EXPECT_EQ(ErrorCode::kOk,
            decode_bytes(Bytes({0, 0, 0, 0, 0, 0, 0, 0, 100, 0, 0, 0, 99, 0, 0, 0, 1, 0}), &ok));
}

TEST(CodecLayout, AckSaysWhetherItAcknowledgesARealTimeFrame) {
  EXPECT_EQ(Bytes({15, 2, 0}), encoded(proto::AckReply{15, 2, false}));
  EXPECT_EQ(Bytes({15, 1, 1}), encoded(proto::AckReply{15, 1, true}));
  expect_range_error<proto::AckReply>({15, 2, 2});
}

TEST(CodecMalformed, ZeroingAxesMustBe1To7) {
  expect_range_error<proto::ZeroingCmd>({0});
  expect_range_error<proto::ZeroingCmd>({8});
}

TEST(CodecMalformed, ReplyEnumsOutsideTheirListsAreOutOfRange) {
  expect_range_error<proto::ErrorReply>({0, 0, 0});  // kOk is not an error
  expect_range_error<proto::ErrorReply>({6, 0, 0});  // unassigned code
  expect_range_error<proto::ErrorReply>({39, 0, 0});
  expect_range_error<proto::AlarmReply>({12, 5});  // after the probe alarms 8..11
  expect_range_error<proto::AlarmReply>({1, 7});
  Bytes status(31, 0);
  status[3] = 100;
  proto::StatusReply s;
  EXPECT_EQ(ErrorCode::kOk, decode_bytes(status, &s));
  status[0] = 6;  // paused: the newest state
  EXPECT_EQ(ErrorCode::kOk, decode_bytes(status, &s));
  status[0] = 7;  // state
  expect_range_error<proto::StatusReply>(status);
}

TEST(CodecMalformed, SessionReplyCapabilitiesOutOfRange) {
  // v2, payload 64, window 8, 16 slots, rx 256, degree 3, 64 points, fw 0.2, travel 1 mm
  // on each axis, feeds 1 um/s: valid; then one field at a time out of range.
  const Bytes ok = {2, 64,   8, 16, 0, 1,    3, 64, 0, 2, 0xE8, 3, 0,
                    0, 0xE8, 3, 0,  0, 0xE8, 3, 0,  0, 1, 0,    1, 0};
  proto::SessionReply r;
  EXPECT_EQ(ErrorCode::kOk, decode_bytes(ok, &r));
  const auto with = [&](size_t at, uint8_t v) {
    Bytes b = ok;
    b[at] = v;
    return b;
  };
  expect_range_error<proto::SessionReply>(with(2, 9));   // window 9
  expect_range_error<proto::SessionReply>(with(1, 65));  // payload 65
  Bytes small_rx = with(4, 69);
  small_rx[5] = 0;  // rx 69 bytes: not even one frame
  expect_range_error<proto::SessionReply>(small_rx);
  expect_range_error<proto::SessionReply>(with(22, 0));  // X/Y feed 0
  Bytes no_travel = ok;
  no_travel[10] = no_travel[11] = 0;  // X travel 0
  expect_range_error<proto::SessionReply>(no_travel);
}

TEST(CodecEncode, EncodeRefusesWhatDecodeRefuses) {
  EXPECT_EQ(ErrorCode::kFieldRange, encode_error(proto::OverrideCmd{250}));
  EXPECT_EQ(ErrorCode::kFieldRange, encode_error(proto::FeedMoveCmd{2000000, 0, 100}));
  EXPECT_EQ(ErrorCode::kFieldRange, encode_error(proto::TextCmd{0, 17, {}}));
  EXPECT_EQ(ErrorCode::kFieldRange, encode_error(proto::SplineHeaderCmd{2, false, 4, 6, 10}));
  EXPECT_EQ(ErrorCode::kFieldRange, encode_error(proto::ErrorReply{ErrorCode::kOk, 0, 0}));
  proto::SplineDataCmd d = {};
  d.control_n = 6;
  d.knot_n = 1;  // 4 + 60 + 4 = 68 bytes
  for (int i = 0; i < 6; ++i) d.control[i].weight_q14 = 16384;
  EXPECT_EQ(ErrorCode::kFieldRange, encode_error(d));
}

TEST(CodecFrame, WriteFrameUsesTheMessagesLetterAndStartByte) {
  proto::AckReply ack = {4, 2, false};
  uint8_t buf[proto::kMaxFrameBytes];
  uint8_t n = 0;
  ASSERT_EQ(ErrorCode::kOk, proto::write_frame(ack, 200, buf, sizeof buf, &n));
  ASSERT_EQ(9, n);
  EXPECT_EQ('*', buf[0]);
  EXPECT_EQ('O', buf[1]);
  EXPECT_EQ(200, buf[2]);
  EXPECT_EQ(3, buf[3]);
  EXPECT_EQ(4, buf[4]);
}

TEST(CodecFrame, WriteFrameIntoATooSmallBufferFailsWithoutWritingPastIt) {
  proto::FeedMoveCmd m = {1, 2, 3};
  uint8_t buf[32];
  memset(buf, 0xAA, sizeof buf);
  uint8_t n = 99;
  EXPECT_EQ(ErrorCode::kPayloadLength, proto::write_frame(m, 1, buf, 15, &n));
  EXPECT_EQ(0, n);
  EXPECT_EQ(0xAA, buf[15]);
}

TEST(CodecFrame, DecodeFrameRefusesAnotherLetter) {
  proto::Parser parser(proto::kCommandStart);
  const Bytes f = test_proto::message_frame(proto::RapidMoveCmd{1, 2}, 3);
  test_proto::Outcome out;
  proto::FeedMoveCmd wrong;
  proto::RapidMoveCmd right;
  for (uint8_t b : f) {
    if (parser.feed(b) == proto::ParseEvent::kFrame) {
      EXPECT_EQ(ErrorCode::kUnknownCommand, proto::decode_frame(parser.frame(), &wrong));
      EXPECT_EQ(ErrorCode::kOk, proto::decode_frame(parser.frame(), &right));
      EXPECT_EQ(2, right.y_um);
    }
  }
}

TEST(CodecFrame, EncodeFrameRejectsOversizePayloadAndBadLetter) {
  uint8_t payload[65] = {};
  uint8_t out[80];
  EXPECT_EQ(0, proto::encode_frame('#', 'D', 0, payload, 65, out, sizeof out));
  EXPECT_EQ(0, proto::encode_frame('#', 'a', 0, payload, 1, out, sizeof out));
  EXPECT_EQ(70, proto::encode_frame('#', 'D', 0, payload, 64, out, sizeof out));
}

// #A: no map (both sides 0) or 2..16 x 2..16 points at least 1 mm apart, the far corner
// inside the coordinate range; #E: 1..8 heights of -1000..1000 um.
TEST(CodecHeightMap, HeaderAndHeightsOutsideTheirRulesAreOutOfRange) {
  EXPECT_EQ(ErrorCode::kOk, encode_error(proto::HeightMapHeaderCmd{0, 0, 0, 0, 0, 0}));
  EXPECT_EQ(ErrorCode::kOk, encode_error(proto::HeightMapHeaderCmd{16, 2, -5000, 0, 1000, 65535}));
  EXPECT_EQ(ErrorCode::kFieldRange,
            encode_error(proto::HeightMapHeaderCmd{0, 3, 0, 0, 5000, 5000}));
  EXPECT_EQ(ErrorCode::kFieldRange,
            encode_error(proto::HeightMapHeaderCmd{1, 3, 0, 0, 5000, 5000}));
  EXPECT_EQ(ErrorCode::kFieldRange, encode_error(proto::HeightMapHeaderCmd{3, 3, 0, 0, 999, 5000}));
  EXPECT_EQ(ErrorCode::kFieldRange,
            encode_error(proto::HeightMapHeaderCmd{17, 3, 0, 0, 5000, 5000}));
  EXPECT_EQ(ErrorCode::kFieldRange,
            encode_error(proto::HeightMapHeaderCmd{16, 2, 990000, 0, 5000, 5000}));  // far corner
  proto::HeightMapDataCmd d{};
  d.height_n = 2;
  d.height_um[0] = -1000;
  d.height_um[1] = 1000;
  EXPECT_EQ(ErrorCode::kOk, encode_error(d));
  d.height_um[1] = 1001;
  EXPECT_EQ(ErrorCode::kFieldRange, encode_error(d));
  d.height_um[1] = 0;
  d.height_n = 9;
  EXPECT_EQ(ErrorCode::kFieldRange, encode_error(d));
  d.height_n = 0;
  EXPECT_EQ(ErrorCode::kFieldRange, encode_error(d));
  // The wire length follows height_n: 2 + 4 n.
  d.height_n = 3;
  EXPECT_EQ(14u, encoded(d).size());
}

TEST(CodecErrors, KnownErrorListMatchesTheDocumentedValues) {
  const int documented[] = {0,  1,  2,  3,  4,  5,  10, 11, 12, 20, 21, 22,
                            23, 24, 30, 31, 32, 33, 34, 35, 36, 37, 38};
  int known = 0;
  for (int c = 0; c < 256; ++c) known += proto::is_known_error(static_cast<uint8_t>(c)) ? 1 : 0;
  EXPECT_EQ(static_cast<int>(sizeof documented / sizeof documented[0]), known);
  for (int c : documented) EXPECT_TRUE(proto::is_known_error(static_cast<uint8_t>(c))) << c;
}

}  // namespace
