// Decodes any frame's payload by start byte and letter, then re-encodes it: used by the
// documentation-example test and the fuzz target (a decoded payload must re-encode to the
// same bytes, or the codec pair disagrees).
#ifndef HOST_TESTS_PROTOCOL_MESSAGE_ROUNDTRIP_H
#define HOST_TESTS_PROTOCOL_MESSAGE_ROUNDTRIP_H

#include <stdint.h>  // uint8_t
#include <string.h>  // memcmp

#include "firmware/protocol/codec.h"          // decode, encode
#include "firmware/protocol/message_table.h"  // PROTO_MESSAGE_TABLE

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

// Picks the message type from start byte and letter (every row of the message table);
// kUnknownCommand if none.
inline RoundTrip round_trip_any(uint8_t start, uint8_t letter, const uint8_t* payload,
                                uint8_t length) {
#define RT_CMD(Type, name, letter_value, role, display, reply, handler, check) \
  if (start == proto::kCommandStart && letter == (letter_value))               \
    return round_trip_as<proto::Type>(payload, length);
#define RT_REPLY(Type, name, letter_value, display, check)     \
  if (start == proto::kReplyStart && letter == (letter_value)) \
    return round_trip_as<proto::Type>(payload, length);
#define RT_SKIP(...)
  PROTO_MESSAGE_TABLE(RT_CMD, RT_REPLY, RT_SKIP, RT_SKIP, RT_SKIP, RT_SKIP)
#undef RT_CMD
#undef RT_REPLY
#undef RT_SKIP
  RoundTrip none = {proto::ErrorCode::kUnknownCommand, false};
  return none;
}

}  // namespace test_proto

#endif  // HOST_TESTS_PROTOCOL_MESSAGE_ROUNDTRIP_H
