// The queue of stored ordered commands (moves, splines, text, pauses, drills ...), kept from
// the moment a frame is acknowledged until its execution finished. Background loop only.
#ifndef FIRMWARE_APP_COMMAND_QUEUE_H
#define FIRMWARE_APP_COMMAND_QUEUE_H

#include <stdint.h>  // int32_t, uint8_t

#include "firmware/protocol/messages.h"  // the commands some items carry

namespace app {

enum class ItemKind : uint8_t {
  kText = 0,        // text: LCD row and characters
  kResolution = 1,  // resolution
  kFeedMove = 2,    // move: XY at its feed
  kRapidMove = 3,   // move: XY at the rapid speed (feed_um_s holds it)
  kZMove = 4,       // z_move
  kZeroing = 5,     // zeroing
  kSpline = 6,      // spline: store slot and feed
  kPause = 7,       // text (row unused): shown until the operator confirms
  kDwell = 8,       // dwell
  kSpindle = 9,     // spindle
  kDrill = 10,      // drill
  kProbe = 11,      // probe: Z down to contact (#Y)
  kMapHeader = 12,  // map_header: a new height map grid, compensation off (#A)
  kMapHeights = 13  // map_heights: heights of the map from an index (#E)
};

// What each kind carries (one of these is in use per item, chosen by its kind). Most carry
// their command's fields as they arrived (the same struct: one copy, docs/protocol.md).
typedef proto::ResolutionCmd ResolutionArgs;
typedef proto::ZMoveCmd ZMoveArgs;
typedef proto::DwellCmd DwellArgs;
typedef proto::SpindleCmd SpindleArgs;
typedef proto::DrillCmd DrillArgs;
typedef proto::HeightMapHeaderCmd MapHeaderArgs;  // cols 0: no map
struct TextArgs {
  uint8_t row;
  uint8_t length;
  char chars[16];
};
struct MoveArgs {
  int32_t x_um;
  int32_t y_um;
  uint16_t feed_um_s;
};
struct ZeroingArgs {
  uint8_t axes;  // bit0 X, bit1 Y, bit2 Z
};
struct SplineArgs {
  uint8_t slot;  // in the SplineStore
  uint16_t feed_um_s;
  int32_t tool_offset_um;  // > 0 left of travel, < 0 right
  uint16_t first_point;    // resume: curve points before this one are walked, not moved to
};

struct ProbeArgs {
  proto::ProbeCmd cmd;  // as it arrived
  uint8_t seen_probes;  // the tick's probe count when the descent was handed over
};

struct MapHeightsArgs {
  uint8_t index;
  uint8_t n;
  int16_t height_um[8];  // proto::kMaxHeightsPerFrame: 18 bytes, as the drill's (the union's)
};

// QueueItem::job_index of a command stored while no #J numbering was active.
static const int32_t kNotInJob = -1;

struct QueueItem {
  ItemKind kind;
  uint8_t seq;        // frame sequence number (last_executed_seq)
  uint8_t stage;      // steps already handed over, for items of several steps (pause, drill)
  int32_t job_index;  // position in the job (#J numbering), kNotInJob before any #J
  uint16_t job_id;    // the job_id of the #J that numbered it
  union {
    TextArgs text;
    ResolutionArgs resolution;
    MoveArgs move;
    ZMoveArgs z_move;
    ZeroingArgs zeroing;
    SplineArgs spline;
    DwellArgs dwell;
    SpindleArgs spindle;
    DrillArgs drill;
    ProbeArgs probe;
    MapHeaderArgs map_header;
    MapHeightsArgs map_heights;
  };
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
  // Forgets the items not handed to the generator yet (a stop: the executing ones stay until
  // the tick has dropped its ring, so the job progress can follow what it still finishes).
  void drop_waiting() { head_ = exec_; }
  // Forgets the items that were executing when the work was dropped (the ring is gone); items
  // stored since stay.
  void drop_executing() { done_ = exec_; }
  // The stored item offset_from_oldest places after the oldest unfinished one, 0 if none.
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
