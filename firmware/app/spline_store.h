// Spline slots filled by #B and #D/#K/#Q frames: checks the header against capacity, the data for
// order and count, coordinates against the travel; validates the finished spline with the core. Two
// slots so the next spline is received while the point generator works on one.
#ifndef FIRMWARE_APP_SPLINE_STORE_H
#define FIRMWARE_APP_SPLINE_STORE_H

#include <stdint.h>  // uint8_t

#include "firmware/core/spline.h"          // Spline
#include "firmware/protocol/messages.h"    // SplineHeaderCmd, SplineDataCmd, SplineCompactCmd ...
#include "firmware/protocol/wire_codes.h"  // ErrorCode

namespace app {

enum class SlotState : uint8_t { kFree = 0, kFilling = 1, kReady = 2, kCancelled = 3 };

class SplineStore {
 public:
  enum { kSlots = 2 };
  SplineStore();
  void clear();
  bool has_free_slot() const;
  uint8_t free_slots() const;
  // #B: checks the header (kFieldRange) and opens a free slot (caller checked there is one).
  proto::ErrorCode begin(const proto::SplineHeaderCmd& header, uint8_t* slot);
  // #D: appends in order (kSplineSequence), coordinates within +-travel (kOutOfTravel). When
  // the last value arrives the spline is validated: kGeometry with *detail set on failure
  // (the slot is then cancelled). *completed tells whether this frame finished the spline.
  proto::ErrorCode add(const proto::SplineDataCmd& data, const int32_t travel_um[2],
                       uint8_t* detail, bool* completed);
  // #K: as add(), the values unpacked from the compact data (kFieldRange, kPayloadLength
  // for data the codec's check lets through but the stored values refuse).
  proto::ErrorCode add_compact(const proto::SplineCompactCmd& data, const int32_t travel_um[2],
                               uint8_t* detail, bool* completed);
  // #Q: as add(), for a spline of contour shape (proto::is_contour_shape) whose last stored
  // point has weight 1.0 and no knots yet (kSplineSequence otherwise); the frame that
  // stores the last point stores every knot too.
  proto::ErrorCode add_contour(const proto::SplineContourCmd& data, const int32_t travel_um[2],
                               uint8_t* detail, bool* completed);
  SlotState state(uint8_t slot) const { return slot < kSlots ? state_[slot] : SlotState::kFree; }
  const core::Spline* spline(uint8_t slot) const { return &spline_[slot]; }
  void release(uint8_t slot);

 private:
  proto::ErrorCode check_next(uint8_t control_index, uint8_t control_n, uint8_t knot_index,
                              uint8_t knot_n) const;
  proto::ErrorCode commit(uint8_t control_n, uint8_t knot_n, uint8_t* detail, bool* completed);
  proto::ErrorCode commit_inside(uint8_t control_index, uint8_t control_n, uint8_t knot_n,
                                 const int32_t travel_um[2], uint8_t* detail, bool* completed);

  core::Spline spline_[kSlots];
  SlotState state_[kSlots];
  uint16_t controls_[kSlots];  // control points received
  uint16_t knots_[kSlots];     // knots received
  uint8_t open_;               // slot being filled, kSlots if none
};

}  // namespace app

#endif  // FIRMWARE_APP_SPLINE_STORE_H
