// Payload codecs for every message of the table (message_table.h): encode checks ranges
// before writing, decode checks length and ranges. Both return a coded error, never trap.
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

// For every message of the table:
// encode(msg, &payload): kOk, or kFieldRange (payload length 0).
// decode(bytes, length, &msg): kOk, kPayloadLength or kFieldRange (msg unspecified).
// check_message(msg): kOk or kFieldRange, what both of them check.
// NOLINTBEGIN(bugprone-macro-parentheses): Type is a type name (`Type*` cannot be bracketed).
#define PROTO_DECLARE_CODEC(Type)                                    \
  ErrorCode encode(const Type& msg, Payload* out);                   \
  ErrorCode decode(const uint8_t* bytes, uint8_t length, Type* msg); \
  ErrorCode check_message(const Type& msg);
#define PROTO_DECLARE_CMD(Type, name, letter, role, display, reply, handler, check) \
  PROTO_DECLARE_CODEC(Type)
#define PROTO_DECLARE_REPLY(Type, name, letter, display, check) PROTO_DECLARE_CODEC(Type)
#define PROTO_DECLARE_SKIP(...)
// NOLINTEND(bugprone-macro-parentheses)
PROTO_MESSAGE_TABLE(PROTO_DECLARE_CMD, PROTO_DECLARE_REPLY, PROTO_DECLARE_SKIP, PROTO_DECLARE_SKIP,
                    PROTO_DECLARE_SKIP, PROTO_DECLARE_SKIP)
#undef PROTO_DECLARE_CODEC
#undef PROTO_DECLARE_CMD
#undef PROTO_DECLARE_REPLY
#undef PROTO_DECLARE_SKIP

// Room for any command of the table (one member per command struct, named m_<Type>).
// NOLINTBEGIN(bugprone-macro-parentheses): Type is a type name.
#define PROTO_ANY_CMD_MEMBER(Type, name, letter, role, display, reply, handler, check) \
  Type m_##Type;
#define PROTO_ANY_CMD_SKIP(...)
// NOLINTEND(bugprone-macro-parentheses)
union AnyCommand {
  PROTO_MESSAGE_TABLE(PROTO_ANY_CMD_MEMBER, PROTO_ANY_CMD_SKIP, PROTO_ANY_CMD_SKIP,
                      PROTO_ANY_CMD_SKIP, PROTO_ANY_CMD_SKIP, PROTO_ANY_CMD_SKIP)
};
#undef PROTO_ANY_CMD_MEMBER
#undef PROTO_ANY_CMD_SKIP

// Decodes the payload as the command of that letter (the table's CMD row), into the union
// member of its type: what decode() of that type returns, or kUnknownCommand when no
// command has the letter. One walker for every command: no decoder per message type.
ErrorCode decode_command(uint8_t letter, const uint8_t* bytes, uint8_t length, AnyCommand* msg);
// The same for the command of that row (command_row(letter), not kNoCommandRow): for a caller
// that has looked the letter up already.
ErrorCode decode_command_row(uint8_t row, const uint8_t* bytes, uint8_t length, AnyCommand* msg);

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
