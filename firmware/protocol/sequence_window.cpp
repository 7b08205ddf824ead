// Sequence classification for the ordered and the real-time streams (see sequence_window.h).
#include "firmware/protocol/sequence_window.h"

namespace proto {

SequenceWindow::SequenceWindow() : next_(0), pending_(false) {}

void SequenceWindow::reset(uint8_t first_seq) {
  next_ = first_seq;
  pending_ = false;
}

SeqClass SequenceWindow::classify(uint8_t seq) const {
  // Distance ahead of the expected seq, modulo 256.
  const uint8_t ahead = (uint8_t)(seq - next_);
  if (ahead == 0) return pending_ ? SeqClass::kPending : SeqClass::kNew;
  if (ahead < kWindowFrames) return SeqClass::kAhead;
  if (ahead >= (uint8_t)(256 - kWindowFrames)) return SeqClass::kDuplicate;
  return SeqClass::kOutOfWindow;
}

void SequenceWindow::accept(uint8_t seq) {
  if (seq != next_) return;
  next_ = (uint8_t)(next_ + 1U);
  pending_ = false;
}

void SequenceWindow::mark_pending(uint8_t seq) {
  if (seq == next_) pending_ = true;
}

RealtimeSequence::RealtimeSequence() : last_(0), any_(false) {}

void RealtimeSequence::reset() {
  any_ = false;
}

SeqClass RealtimeSequence::classify(uint8_t seq) const {
  if (!any_) return SeqClass::kNew;
  const uint8_t ahead = (uint8_t)(seq - last_);
  if (ahead == 0) return SeqClass::kDuplicate;
  if (ahead < 128) return SeqClass::kNew;
  return SeqClass::kStale;
}

void RealtimeSequence::accept(uint8_t seq) {
  last_ = seq;
  any_ = true;
}

}  // namespace proto
