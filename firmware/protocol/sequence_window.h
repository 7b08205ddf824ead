// Sequence bookkeeping the dispatcher consults before acting on a frame: is this ordered
// frame new, a duplicate of one already accepted, or outside the window; is this real-time
// frame newer than the last. 8-bit sequence numbers, wrapping 255 -> 0.
#ifndef FIRMWARE_PROTOCOL_SEQUENCE_WINDOW_H
#define FIRMWARE_PROTOCOL_SEQUENCE_WINDOW_H

#include <stdint.h>  // uint8_t

#include "firmware/protocol/wire_codes.h"  // kWindowFrames

namespace proto {

enum class SeqClass : uint8_t {
  kNew = 0,          // the expected seq: store it, then accept()
  kDuplicate = 1,    // accepted already (within the window behind): ack again, do not run
  kPending = 2,      // the frame held with its ack delayed: ignore, its ack will come
  kAhead = 3,        // up to kWindowFrames-1 ahead: an earlier frame was lost (kSeqGap)
  kOutOfWindow = 4,  // anything else (kSeqOutOfWindow)
  kStale = 5         // real-time only: older than the last accepted (kSeqStale)
};

// The ordered (queued) stream: accepts exactly next_expected(), in order.
class SequenceWindow {
 public:
  SequenceWindow();
  // Starts a stream whose first ordered frame will carry first_seq.
  void reset(uint8_t first_seq);
  SeqClass classify(uint8_t seq) const;
  // The frame with next_expected() is stored: advance. Other seqs are ignored.
  void accept(uint8_t seq);
  // The frame with next_expected() is held without room: later copies classify kPending.
  void mark_pending(uint8_t seq);
  void clear_pending() { pending_ = false; }
  bool pending() const { return pending_; }
  uint8_t next_expected() const { return next_; }
  // Seq of the newest accepted frame (next_expected() - 1).
  uint8_t last_accepted() const { return (uint8_t)(next_ - 1U); }

 private:
  uint8_t next_;
  bool pending_;
};

// The real-time stream: any newer seq (up to 127 ahead of the last) is accepted, the last
// one again is a duplicate, older ones are stale. Lost real-time frames leave no gap.
class RealtimeSequence {
 public:
  RealtimeSequence();
  // Forgets the last seq: the next real-time frame is new whatever its seq.
  void reset();
  SeqClass classify(uint8_t seq) const;
  void accept(uint8_t seq);

 private:
  uint8_t last_;
  bool any_;
};

}  // namespace proto

#endif  // FIRMWARE_PROTOCOL_SEQUENCE_WINDOW_H
