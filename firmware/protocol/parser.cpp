// Incremental frame parser (see parser.h). Bytes sit in one frame-sized buffer; buf_[0] is
// always a start byte while count_ > 0, so a rejection re-scans from buf_[1].
#include "firmware/protocol/parser.h"

#include <string.h>  // memmove, memset

#include "firmware/protocol/crc16.h"  // crc16

namespace proto {

// Adds one to a saturating 16-bit counter.
static void count_up(uint16_t* counter) {
  if (*counter != 0xFFFFU) ++*counter;
}

Parser::Parser(uint8_t start_byte) : start_(start_byte), last_error_(ErrorCode::kOk) {
  rejected_total_ = 0;
  skipped_bytes_ = 0;
  memset(errors_, 0, sizeof errors_);
  reset();
}

void Parser::reset() {
  count_ = 0;
  parsed_ = 0;
  consumed_ = 0;
  expiring_ = false;
  memset(&frame_, 0, sizeof frame_);
}

uint16_t Parser::error_count(ErrorCode code) const {
  const uint8_t index = (uint8_t)code;
  return index < kParserErrorCount ? errors_[index] : 0;
}

void Parser::note_rx_error() {
  count_up(&errors_[(uint8_t)ErrorCode::kRxOverrun]);
  count_up(&rejected_total_);
  last_error_ = ErrorCode::kRxOverrun;
}

// Removes the first n buffered bytes.
void Parser::drop_front(uint8_t n) {
  if (n >= count_) {
    count_ = 0;
  } else {
    memmove(buf_, buf_ + n, (size_t)(count_ - n));
    count_ = (uint8_t)(count_ - n);
  }
  parsed_ = 0;
}

// Drops bytes before the first start byte at or after index from; bytes from index `from`
// on are counted as garbage.
void Parser::skip_to_start(uint8_t from) {
  uint8_t i = from;
  while (i < count_ && buf_[i] != start_) ++i;
  for (uint8_t k = from; k < i; ++k) count_up(&skipped_bytes_);
  drop_front(i);
}

// Drops the candidate's start byte and resumes the hunt right after it.
ParseEvent Parser::reject(ErrorCode code) {
  last_error_ = code;
  count_up(&errors_[(uint8_t)code]);
  count_up(&rejected_total_);
  skip_to_start(1);
  return ParseEvent::kRejected;
}

ParseEvent Parser::feed(uint8_t byte) {
  expiring_ = false;
  if (consumed_ != 0) {
    drop_front(consumed_);
    consumed_ = 0;
  }
  if (count_ >= kMaxFrameBytes) {
    // Caller skipped poll(): never write past the buffer, count the lost byte.
    note_rx_error();
    return run();
  }
  buf_[count_++] = byte;
  return run();
}

ParseEvent Parser::poll() {
  if (consumed_ != 0) {
    drop_front(consumed_);
    consumed_ = 0;
  }
  const ParseEvent ev = run();
  if (ev != ParseEvent::kNone || !expiring_) return ev;
  // After a silence every candidate left over from the re-scan is stale too.
  if (count_ > 0) return reject(ErrorCode::kTruncated);
  expiring_ = false;
  return ParseEvent::kNone;
}

ParseEvent Parser::expire() {
  if (consumed_ != 0) {
    drop_front(consumed_);
    consumed_ = 0;
  }
  if (count_ == 0) return ParseEvent::kNone;
  expiring_ = true;
  return reject(ErrorCode::kTruncated);
}

// Checks buffered bytes one at a time until a frame completes, a candidate fails, or the
// buffer is exhausted.
ParseEvent Parser::run() {
  if (count_ > 0 && buf_[0] != start_) skip_to_start(0);
  while (parsed_ < count_) {
    const uint8_t at = parsed_;
    const uint8_t byte = buf_[at];
    if (at == 1 && !is_frame_letter(byte)) return reject(ErrorCode::kBadLetter);
    if (at == 3 && byte > kMaxPayload) return reject(ErrorCode::kLengthTooLarge);
    parsed_ = (uint8_t)(at + 1);
    if (parsed_ < kHeaderBytes) continue;
    const uint8_t length = buf_[3];
    const uint8_t total = (uint8_t)(kHeaderBytes + length + kCrcBytes);
    if (parsed_ < total) continue;
    const uint16_t expected = crc16(buf_, (size_t)kHeaderBytes + length);
    const uint16_t got =
        (uint16_t)(buf_[kHeaderBytes + length] | ((uint16_t)buf_[kHeaderBytes + length + 1] << 8));
    if (expected != got) return reject(ErrorCode::kBadCrc);
    frame_.start = buf_[0];
    frame_.letter = buf_[1];
    frame_.seq = buf_[2];
    frame_.length = length;
    frame_.kind = start_ == kCommandStart ? command_kind(buf_[1]) : FrameKind::kImmediate;
    frame_.payload = buf_ + kHeaderBytes;
    consumed_ = total;
    return ParseEvent::kFrame;
  }
  return ParseEvent::kNone;
}

}  // namespace proto
