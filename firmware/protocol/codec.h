// Payload codecs for every message in messages.h: encode checks ranges before writing, decode
// checks length and ranges before filling the struct. Both return a coded error, never trap.
#ifndef FIRMWARE_PROTOCOL_CODEC_H
#define FIRMWARE_PROTOCOL_CODEC_H

#include <stdint.h>  // uint8_t

#include "firmware/protocol/frame.h"     // encode_frame, Frame
#include "firmware/protocol/messages.h"  // message structs

namespace proto {

// A payload under construction or as received.
struct Payload {
  uint8_t length;
  uint8_t bytes[kMaxPayload];
};

// encode(msg, &payload): kOk, or kFieldRange (payload untouched in content, length 0).
// decode(bytes, length, &msg): kOk, kPayloadLength or kFieldRange (msg unspecified).
// Type is a type name: it cannot be parenthesised in `Type*`.
// NOLINTBEGIN(bugprone-macro-parentheses)
#define PROTO_DECLARE_CODEC(Type)                  \
  ErrorCode encode(const Type& msg, Payload* out); \
  ErrorCode decode(const uint8_t* bytes, uint8_t length, Type* msg);
// NOLINTEND(bugprone-macro-parentheses)

PROTO_DECLARE_CODEC(SessionCmd)
PROTO_DECLARE_CODEC(StatusCmd)
PROTO_DECLARE_CODEC(HoldCmd)
PROTO_DECLARE_CODEC(ResumeCmd)
PROTO_DECLARE_CODEC(AbortCmd)
PROTO_DECLARE_CODEC(ClearAlarmCmd)
PROTO_DECLARE_CODEC(OverrideCmd)
PROTO_DECLARE_CODEC(TextCmd)
PROTO_DECLARE_CODEC(SplineHeaderCmd)
PROTO_DECLARE_CODEC(SplineDataCmd)
PROTO_DECLARE_CODEC(ResolutionCmd)
PROTO_DECLARE_CODEC(FeedMoveCmd)
PROTO_DECLARE_CODEC(RapidMoveCmd)
PROTO_DECLARE_CODEC(ZMoveCmd)
PROTO_DECLARE_CODEC(ZeroingCmd)
PROTO_DECLARE_CODEC(PauseCmd)
PROTO_DECLARE_CODEC(DwellCmd)
PROTO_DECLARE_CODEC(SpindleCmd)
PROTO_DECLARE_CODEC(DrillCmd)
PROTO_DECLARE_CODEC(AckReply)
PROTO_DECLARE_CODEC(ErrorReply)
PROTO_DECLARE_CODEC(SessionReply)
PROTO_DECLARE_CODEC(StatusReply)
PROTO_DECLARE_CODEC(AlarmReply)

#undef PROTO_DECLARE_CODEC

// Decodes a received frame's payload into msg after checking the letter matches.
template <typename Msg>
ErrorCode decode_frame(const Frame& frame, Msg* msg) {
  if (frame.letter != (uint8_t)Msg::kLetter) return ErrorCode::kUnknownCommand;
  return decode(frame.payload, frame.length, msg);
}

// Encodes msg as a complete frame (start byte and letter from Msg) into out. On kOk *size
// is the frame size; kPayloadLength when out is too small.
template <typename Msg>
ErrorCode write_frame(const Msg& msg, uint8_t seq, uint8_t* out, uint16_t out_capacity,
                      uint8_t* size) {
  Payload payload;
  const ErrorCode error = encode(msg, &payload);
  *size = 0;
  if (error != ErrorCode::kOk) return error;
  const uint8_t n = encode_frame((uint8_t)Msg::kStart, (uint8_t)Msg::kLetter, seq, payload.bytes,
                                 payload.length, out, out_capacity);
  if (n == 0) return ErrorCode::kPayloadLength;
  *size = n;
  return ErrorCode::kOk;
}

// True for the values ErrorCode defines (a decoder of *E / *? rejects others).
bool is_known_error(uint8_t code);

}  // namespace proto

#endif  // FIRMWARE_PROTOCOL_CODEC_H
