// The queue of stored ordered commands (moves, splines, text, resolution, zeroing), kept from
// the moment a frame is acknowledged until its execution finished. Background loop only.
#ifndef FIRMWARE_APP_COMMAND_QUEUE_H
#define FIRMWARE_APP_COMMAND_QUEUE_H

#include <stdint.h>  // int32_t, uint8_t

namespace app {

enum class ItemKind : uint8_t {
  kText = 0,        // row in `small`, text in text[0..text_length)
  kResolution = 1,  // max step in feed_um_s, chord tolerance in extra
  kFeedMove = 2,    // XY to (a, b) at feed_um_s
  kRapidMove = 3,   // XY to (a, b) at the rapid speed
  kZMove = 4,       // Z to a at feed_um_s
  kZeroing = 5,     // axes mask in `small`
  kSpline = 6       // spline store slot in `small`, feed in feed_um_s
};

struct QueueItem {
  ItemKind kind;
  uint8_t seq;          // frame sequence number (last_executed_seq)
  uint8_t small;        // row / axes / slot
  uint8_t text_length;  // kText
  int32_t a;
  int32_t b;
  uint16_t feed_um_s;
  uint16_t extra;
  char text[16];
};

// Fixed ring of items with three cursors: done <= exec <= head. [done, exec) are executing
// (points in the coordinate ring), [exec, head) wait for the point generator.
class CommandQueue {
 public:
  enum { kCapacity = 16 };
  CommandQueue() : head_(0), exec_(0), done_(0) {}
  void clear() { head_ = exec_ = done_ = 0; }
  uint8_t free_slots() const { return (uint8_t)(kCapacity - (uint8_t)(head_ - done_)); }
  bool empty() const { return head_ == done_; }
  // Stores a copy; false when full.
  bool push(const QueueItem& item) {
    if (free_slots() == 0) return false;
    items_[head_ % kCapacity] = item;
    ++head_;
    return true;
  }
  // Next item for the generator, 0 if none.
  QueueItem* to_execute() { return exec_ == head_ ? 0 : &items_[exec_ % kCapacity]; }
  void executed() {
    if (exec_ != head_) ++exec_;
  }
  // Oldest unfinished item (executing or waiting), 0 if none.
  const QueueItem* oldest() const { return done_ == head_ ? 0 : &items_[done_ % kCapacity]; }
  // Items handed to the generator and not finished yet.
  uint8_t in_flight() const { return (uint8_t)(exec_ - done_); }
  void finished() {
    if (done_ != exec_) ++done_;
  }
  // The stored item offset_from_oldest places after the oldest unfinished one (0: the
  // oldest; size() - 1: the newest), for checks such as "zeroing queued"; 0 if none.
  const QueueItem* at(uint8_t offset_from_oldest) const {
    if (offset_from_oldest >= (uint8_t)(head_ - done_)) return 0;
    return &items_[(uint8_t)(done_ + offset_from_oldest) % kCapacity];
  }
  uint8_t size() const { return (uint8_t)(head_ - done_); }

 private:
  uint8_t head_;
  uint8_t exec_;
  uint8_t done_;
  QueueItem items_[kCapacity];
};

}  // namespace app

#endif  // FIRMWARE_APP_COMMAND_QUEUE_H
