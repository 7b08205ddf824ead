// One frame as the parser hands it out, and the frame writer shared by firmware and host.
// Layout: start, letter, seq, length, payload[length], CRC-16 low byte, CRC-16 high byte.
#ifndef FIRMWARE_PROTOCOL_FRAME_H
#define FIRMWARE_PROTOCOL_FRAME_H

#include <stdint.h>  // uint8_t

#include "firmware/protocol/wire_codes.h"  // kMaxPayload, FrameKind

namespace proto {

// A received, CRC-checked frame. payload points into the parser's buffer and stays valid
// until the next Parser::feed()/poll()/expire() call.
struct Frame {
  uint8_t start;   // kCommandStart or kReplyStart
  uint8_t letter;  // command or reply letter
  uint8_t seq;     // sequence number
  uint8_t length;  // payload bytes, 0..kMaxPayload
  FrameKind kind;  // command_kind(letter) for commands, kImmediate for replies
  const uint8_t* payload;
};

// Writes a complete frame into out[0..out_capacity). Returns the frame size in bytes, or 0
// (nothing usable written) when length > kMaxPayload, the letter is not 'A'..'Z'/'?', or the
// frame does not fit.
uint8_t encode_frame(uint8_t start, uint8_t letter, uint8_t seq, const uint8_t* payload,
                     uint8_t length, uint8_t* out, uint16_t out_capacity);

// True for the letters a frame may carry: 'A'..'Z' and '?'.
bool is_frame_letter(uint8_t letter);

}  // namespace proto

#endif  // FIRMWARE_PROTOCOL_FRAME_H
