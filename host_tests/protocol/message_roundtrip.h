// Decodes any frame's payload by start byte and letter, then re-encodes it: used by the
// documentation-example test and the fuzz target (a decoded payload must re-encode to the
// same bytes, or the codec pair disagrees).
#ifndef HOST_TESTS_PROTOCOL_MESSAGE_ROUNDTRIP_H
#define HOST_TESTS_PROTOCOL_MESSAGE_ROUNDTRIP_H

#include <stdint.h>  // uint8_t
#include <string.h>  // memcmp

#include "firmware/protocol/codec.h"  // decode, encode

namespace test_proto {

// Result of a round trip: the decode code, and whether re-encoding reproduced the payload.
struct RoundTrip {
  proto::ErrorCode decode;
  bool same_bytes;
};

template <typename Msg>
RoundTrip round_trip_as(const uint8_t* payload, uint8_t length) {
  Msg msg;
  RoundTrip r;
  r.decode = proto::decode(payload, length, &msg);
  r.same_bytes = false;
  if (r.decode != proto::ErrorCode::kOk) return r;
  proto::Payload again;
  if (proto::encode(msg, &again) != proto::ErrorCode::kOk) return r;
  r.same_bytes =
      again.length == length && (length == 0 || memcmp(again.bytes, payload, length) == 0);
  return r;
}

// Picks the message type from start byte and letter; kUnknownCommand if none.
inline RoundTrip round_trip_any(uint8_t start, uint8_t letter, const uint8_t* payload,
                                uint8_t length) {
  if (start == proto::kCommandStart) {
    switch (letter) {
      case proto::kCmdSession:
        return round_trip_as<proto::SessionCmd>(payload, length);
      case proto::kCmdStatus:
        return round_trip_as<proto::StatusCmd>(payload, length);
      case proto::kCmdHold:
        return round_trip_as<proto::HoldCmd>(payload, length);
      case proto::kCmdResume:
        return round_trip_as<proto::ResumeCmd>(payload, length);
      case proto::kCmdAbort:
        return round_trip_as<proto::AbortCmd>(payload, length);
      case proto::kCmdOverride:
        return round_trip_as<proto::OverrideCmd>(payload, length);
      case proto::kCmdClearAlarm:
        return round_trip_as<proto::ClearAlarmCmd>(payload, length);
      case proto::kCmdText:
        return round_trip_as<proto::TextCmd>(payload, length);
      case proto::kCmdSplineHeader:
        return round_trip_as<proto::SplineHeaderCmd>(payload, length);
      case proto::kCmdSplineData:
        return round_trip_as<proto::SplineDataCmd>(payload, length);
      case proto::kCmdResolution:
        return round_trip_as<proto::ResolutionCmd>(payload, length);
      case proto::kCmdFeedMove:
        return round_trip_as<proto::FeedMoveCmd>(payload, length);
      case proto::kCmdRapidMove:
        return round_trip_as<proto::RapidMoveCmd>(payload, length);
      case proto::kCmdZMove:
        return round_trip_as<proto::ZMoveCmd>(payload, length);
      case proto::kCmdZeroing:
        return round_trip_as<proto::ZeroingCmd>(payload, length);
      case proto::kCmdPause:
        return round_trip_as<proto::PauseCmd>(payload, length);
      case proto::kCmdDwell:
        return round_trip_as<proto::DwellCmd>(payload, length);
      case proto::kCmdSpindle:
        return round_trip_as<proto::SpindleCmd>(payload, length);
      case proto::kCmdDrill:
        return round_trip_as<proto::DrillCmd>(payload, length);
      case proto::kCmdJobMark:
        return round_trip_as<proto::JobMarkCmd>(payload, length);
      default:
        break;
    }
  } else if (start == proto::kReplyStart) {
    switch (letter) {
      case proto::kReplyAck:
        return round_trip_as<proto::AckReply>(payload, length);
      case proto::kReplyError:
        return round_trip_as<proto::ErrorReply>(payload, length);
      case proto::kReplySession:
        return round_trip_as<proto::SessionReply>(payload, length);
      case proto::kReplyStatus:
        return round_trip_as<proto::StatusReply>(payload, length);
      case proto::kReplyAlarm:
        return round_trip_as<proto::AlarmReply>(payload, length);
      default:
        break;
    }
  }
  RoundTrip none = {proto::ErrorCode::kUnknownCommand, false};
  return none;
}

}  // namespace test_proto

#endif  // HOST_TESTS_PROTOCOL_MESSAGE_ROUNDTRIP_H
