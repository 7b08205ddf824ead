// Frame writer and letter classification (see frame.h, wire_codes.h).
#include "firmware/protocol/frame.h"

#include <string.h>  // memcpy

#include "firmware/protocol/crc16.h"  // crc16

namespace proto {

bool is_frame_letter(uint8_t letter) {
  return (letter >= 'A' && letter <= 'Z') || letter == '?';
}

uint8_t command_row(uint8_t letter) {
#define PROTO_ROW_LETTER(Type, name, letter_value, role, display, reply, handler, check) \
  (uint8_t)(letter_value),
#define PROTO_ROW_SKIP(...)
  static const uint8_t kLetters[] = {PROTO_MESSAGE_TABLE(PROTO_ROW_LETTER, PROTO_ROW_SKIP,
                                                         PROTO_ROW_SKIP, PROTO_ROW_SKIP,
                                                         PROTO_ROW_SKIP, PROTO_ROW_SKIP)};
#undef PROTO_ROW_LETTER
#undef PROTO_ROW_SKIP
  for (uint8_t i = 0; i < (uint8_t)sizeof kLetters; ++i) {
    if (kLetters[i] == letter) return i;
  }
  return kNoCommandRow;
}

// The kind follows from the command's role (the queued roles differ only in what they do).
FrameKind command_kind(uint8_t letter) {
  switch (command_role(letter)) {
    case CommandRole::kUnknown:
      return FrameKind::kUnknown;
    case CommandRole::kImmediate:
      return FrameKind::kImmediate;
    case CommandRole::kRealtime:
      return FrameKind::kRealtime;
    default:
      return FrameKind::kQueued;
  }
}

const char* message_name(uint8_t start, uint8_t letter) {
#define PROTO_NAME_CMD(Type, name, letter_value, role, display, reply, handler, check) \
  if (start == kCommandStart && letter == (letter_value)) return display;
#define PROTO_NAME_REPLY(Type, name, letter_value, display, check) \
  if (start == kReplyStart && letter == (letter_value)) return display;
#define PROTO_NAME_SKIP(...)
  PROTO_MESSAGE_TABLE(PROTO_NAME_CMD, PROTO_NAME_REPLY, PROTO_NAME_SKIP, PROTO_NAME_SKIP,
                      PROTO_NAME_SKIP, PROTO_NAME_SKIP)
#undef PROTO_NAME_CMD
#undef PROTO_NAME_REPLY
#undef PROTO_NAME_SKIP
  return 0;
}

uint8_t encode_frame(uint8_t start, uint8_t letter, uint8_t seq, const uint8_t* payload,
                     uint8_t length, uint8_t* out, uint16_t out_capacity) {
  const uint16_t total = (uint16_t)(kHeaderBytes + length + kCrcBytes);
  if (length > kMaxPayload || !is_frame_letter(letter) || out == 0 || total > out_capacity) {
    return 0;
  }
  if (length > 0 && payload == 0) return 0;
  out[0] = start;
  out[1] = letter;
  out[2] = seq;
  out[3] = length;
  if (length > 0) memcpy(out + kHeaderBytes, payload, length);
  const uint16_t crc = crc16(out, (size_t)kHeaderBytes + length);
  out[kHeaderBytes + length] = (uint8_t)(crc & 0xFFU);
  out[kHeaderBytes + length + 1] = (uint8_t)(crc >> 8);
  return (uint8_t)total;
}

}  // namespace proto
