// Test helpers: build frames as byte vectors and run a parser over a byte stream.
#ifndef HOST_TESTS_PROTOCOL_FRAME_HELPERS_H
#define HOST_TESTS_PROTOCOL_FRAME_HELPERS_H

#include <cstdint>  // uint8_t
#include <vector>   // std::vector

#include "firmware/protocol/codec.h"   // write_frame
#include "firmware/protocol/parser.h"  // Parser

namespace test_proto {

typedef std::vector<uint8_t> Bytes;

// A whole frame with an arbitrary payload (no codec checks).
inline Bytes raw_frame(uint8_t start, uint8_t letter, uint8_t seq, const Bytes& payload) {
  Bytes out(proto::kMaxFrameBytes);
  const uint8_t n =
      proto::encode_frame(start, letter, seq, payload.data(), static_cast<uint8_t>(payload.size()),
                          out.data(), static_cast<uint16_t>(out.size()));
  out.resize(n);
  return out;
}

// A whole frame of a typed message; empty if the codec refuses it.
template <typename Msg>
Bytes message_frame(const Msg& msg, uint8_t seq) {
  Bytes out(proto::kMaxFrameBytes);
  uint8_t n = 0;
  if (proto::write_frame(msg, seq, out.data(), static_cast<uint16_t>(out.size()), &n) !=
      proto::ErrorCode::kOk) {
    return Bytes();
  }
  out.resize(n);
  return out;
}

// What a parser produced: each good frame (letter, seq, payload) and each rejection code.
struct Received {
  uint8_t letter;
  uint8_t seq;
  Bytes payload;
};

struct Outcome {
  std::vector<Received> frames;
  std::vector<proto::ErrorCode> rejections;
};

// Handles one parser event and drains the backlog.
inline void drain(proto::Parser& parser, proto::ParseEvent ev, Outcome* out) {
  while (ev != proto::ParseEvent::kNone) {
    if (ev == proto::ParseEvent::kFrame) {
      const proto::Frame& f = parser.frame();
      Received r;
      r.letter = f.letter;
      r.seq = f.seq;
      r.payload.assign(f.payload, f.payload + f.length);
      out->frames.push_back(r);
    } else {
      out->rejections.push_back(parser.last_error());
    }
    ev = parser.poll();
  }
}

// Feeds bytes one at a time (the firmware's way).
inline Outcome feed_all(proto::Parser& parser, const Bytes& bytes) {
  Outcome out;
  for (uint8_t b : bytes) drain(parser, parser.feed(b), &out);
  return out;
}

inline Bytes concat(const std::vector<Bytes>& parts) {
  Bytes out;
  for (const Bytes& p : parts) out.insert(out.end(), p.begin(), p.end());
  return out;
}

}  // namespace test_proto

#endif  // HOST_TESTS_PROTOCOL_FRAME_HELPERS_H
