// Incremental frame parser: one byte at a time, constant memory, CRC-checked, resynchronising
// at the next start byte after garbage or a rejected frame (bytes after a false start are
// re-scanned, so a start byte inside a corrupted frame cannot cost the next real frame).
#ifndef FIRMWARE_PROTOCOL_PARSER_H
#define FIRMWARE_PROTOCOL_PARSER_H

#include <stdint.h>  // uint8_t, uint16_t

#include "firmware/protocol/frame.h"       // Frame
#include "firmware/protocol/wire_codes.h"  // ErrorCode, kMaxFrameBytes

namespace proto {

// What a feed()/poll()/expire() call produced.
enum class ParseEvent : uint8_t {
  kNone = 0,     // nothing complete yet (all buffered bytes consumed)
  kFrame = 1,    // frame() holds a valid frame
  kRejected = 2  // a frame candidate was dropped; last_error() says why
};

class Parser {
 public:
  // start_byte: kCommandStart in the firmware, kReplyStart in the host.
  explicit Parser(uint8_t start_byte);

  // Adds one received byte and parses. After any result other than kNone, call poll() until
  // it returns kNone before the next feed(): bytes re-scanned after a rejection may hold more.
  ParseEvent feed(uint8_t byte);
  // Continues with bytes already buffered (re-scan backlog); kNone when there are none left.
  ParseEvent poll();
  // No byte for kInterByteTimeoutMs: drops the partial frame (kTruncated) and re-scans its
  // bytes; then call poll() until kNone as after feed(). Complete frames found by the re-scan
  // are still delivered; partial ones left over are dropped too (each counted kTruncated),
  // so afterwards in_frame() is false. Returns kNone when no frame was in progress.
  ParseEvent expire();
  // Counts a receive error reported by the UART (overrun/framing) as kRxOverrun.
  void note_rx_error();
  // Forgets everything buffered (counters kept).
  void reset();

  // The frame of the last kFrame result; valid until the next feed/poll/expire/reset.
  const Frame& frame() const { return frame_; }
  // Code of the last rejection (kOk if none yet).
  ErrorCode last_error() const { return last_error_; }
  // Rejections per parser code (index = code value, 0..kParserErrorCount-1), saturating.
  uint16_t error_count(ErrorCode code) const;
  // Total rejections (all codes), saturating.
  uint16_t rejected_total() const { return rejected_total_; }
  // Bytes skipped while hunting for a start byte, saturating.
  uint16_t skipped_bytes() const { return skipped_bytes_; }
  // True while a partial frame is buffered (for the inter-byte timeout).
  bool in_frame() const { return count_ > 0; }

 private:
  ParseEvent run();
  ParseEvent reject(ErrorCode code);
  void drop_front(uint8_t n);
  void skip_to_start(uint8_t from);

  uint8_t start_;
  uint8_t count_;     // bytes in buf_
  uint8_t parsed_;    // bytes of buf_ already checked as the current candidate
  uint8_t consumed_;  // bytes of the frame handed out, dropped at the next call
  bool expiring_;     // expire() in progress: drop leftover partial candidates too
  ErrorCode last_error_;
  uint16_t rejected_total_;
  uint16_t skipped_bytes_;
  uint16_t errors_[kParserErrorCount];
  Frame frame_;
  uint8_t buf_[kMaxFrameBytes];
};

}  // namespace proto

#endif  // FIRMWARE_PROTOCOL_PARSER_H
